#pragma once

#include <deal.II/base/quadrature.h>
#include <deal.II/fe/fe.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/grid/reference_cell.h>
#include <deal.II/grid/tria.h>

#include <memory>
#include <string>

namespace dualcontact
{
  namespace fem
  {
    /**
     * The kind of cells a body's mesh is made of, and everything that
     * depends on it: the finite element (FE_Q on quadrilaterals and
     * hexahedra, FE_SimplexP on triangles and tetrahedra), the mapping
     * (MappingQ, MappingFE(FE_SimplexP(1))), the Gauss rules of cells and
     * faces (QGauss, QGaussSimplex) and the geometry of the reference cell
     * (which dofs lie on a face).  The one place where the code asks "what
     * cells is this?", so that assembly, contact, output and the mesh checks
     * are written once for both families.
     *
     * Simplex meshes are mapped affinely (MappingFE of degree 1) whatever
     * the element's degree: a curved boundary is the polygon of its
     * vertices (which refinement places on the manifold), as the contact
     * search sees every face (flat, contact::FaceGeometry) anyway.
     */
    template <int dim>
    class CellFamily
    {
    public:
      /** The family of @p cell_type (a hypercube or a simplex). */
      explicit CellFamily(const dealii::ReferenceCell &cell_type);

      /**
       * The family of the cells of @p triangulation; a mesh mixing cell
       * types (or with pyramids or wedges) is refused naming @p mesh_name
       * and the counts of each type.  All processes of a distributed mesh
       * must have the same family (an empty local part is a hypercube).
       */
      CellFamily(const dealii::Triangulation<dim> &triangulation,
                 const std::string                &mesh_name);

      /** Triangles or tetrahedra (else quadrilaterals or hexahedra). */
      bool
      is_simplex() const;

      /** The reference cell of the cells and of their faces. */
      const dealii::ReferenceCell &
      cell_type() const;
      dealii::ReferenceCell
      face_type() const;

      /** "hexahedra", "triangles", ...: the cells in words (plural). */
      std::string
      cells_in_words() const;

      /** FE_Q(degree) or FE_SimplexP(degree), scalar. */
      std::unique_ptr<dealii::FiniteElement<dim>>
      scalar_element(const unsigned int degree) const;

      /**
       * The mapping of an element of @p degree: MappingQ(degree) on
       * hypercubes, the affine MappingFE(FE_SimplexP(1)) on simplices.
       */
      std::unique_ptr<dealii::Mapping<dim>>
      mapping(const unsigned int degree) const;

      /** The degree of mapping(degree): @p degree, or 1 on simplices. */
      unsigned int
      mapping_degree(const unsigned int degree) const;

      /**
       * Gauss rules on the cell and on a face exact for polynomials of
       * degree 2 n - 1 (QGauss with n points per direction, QGaussSimplex
       * of the same exactness).
       */
      dealii::Quadrature<dim>
      cell_quadrature(const unsigned int n_points_1d) const;
      dealii::Quadrature<dim - 1>
      face_quadrature(const unsigned int n_points_1d) const;

      /**
       * The unit-cell point of @p cell that @p mapping (mapping() of this
       * family) maps to @p x: the inverse of the affine map of the
       * vertices on simplices (deal.II 9.4's MappingFE does not invert),
       * Mapping::transform_real_to_unit_cell() on hypercubes.
       */
      dealii::Point<dim>
      unit_point(const dealii::Mapping<dim> &mapping,
                 const typename dealii::Triangulation<dim>::cell_iterator &cell,
                 const dealii::Point<dim> &x) const;

      /**
       * The midpoint rule on a face cut into n^(dim - 1) equal pieces
       * (squares, or triangles of the face split at n + 1 points per
       * edge): where a face is integrated with a discontinuous integrand
       * (a level set through it), all weights equal.
       */
      dealii::Quadrature<dim - 1>
      face_midpoint_rule(const unsigned int n) const;

      /**
       * Whether dof @p i of @p fe has its support on face @p face_no: a
       * nodal element's dof lies on a face when its unit support point
       * does.  FiniteElement::has_support_on_face() cannot be used: deal.II
       * 9.4's FE_SimplexP answers true for every dof and face.
       */
      static bool
      is_face_dof(const dealii::FiniteElement<dim> &fe,
                  const unsigned int                i,
                  const unsigned int                face_no);

      /**
       * The function chi_k whose integral over a face is the lumped weight
       * of the face's dof @p k (a contact node's weight, w_j = the sum over
       * its faces of the integral of chi_j), at quadrature point @p q of
       * @p values (reinitialized on the face): the shape function itself,
       * except on quadratic triangles (the faces of P2 tetrahedra), whose
       * vertex shape functions integrate to zero (and the midpoints' to
       * A / 3): there chi_k is constant, 1/12 at a vertex and 1/4 at an
       * edge midpoint, the integrals of the linear hats of the face split
       * at its midpoints into four triangles (positive, summing to one,
       * the P1 lumping of the refined face).  Quadratic lines (P2
       * triangles) integrate to L/6 and 2L/3: no exception.
       */
      static double
      lumping_function(const dealii::FEFaceValues<dim> &values,
                       const unsigned int               k,
                       const unsigned int               q);

      /**
       * The number of subdivisions of a cell in the output of a degree-p
       * field: p (every node a patch point) on hypercubes; 1 on simplices,
       * whose patches deal.II 9.4 writes at the vertices only (a P2 field
       * is shown linearly between the vertices).
       */
      unsigned int
      output_subdivisions(const unsigned int degree) const;

    private:
      dealii::ReferenceCell cell_type_;
    };
  } // namespace fem
} // namespace dualcontact
