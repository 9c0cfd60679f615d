#pragma once

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/types.h>

#include <io/contact_surface_mesh.h>

#include <array>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace dualcontact
{
  namespace io
  {
    /**
     * The values of the `status' field of the contact-surface file.  A
     * node is separated when its normal multiplier is not above the status
     * tolerance times the pair's largest one.  A node in contact under a
     * friction law (Tresca, Coulomb) sticks while its tangential
     * multiplier is inside the slip bound and slips on it; a node in
     * contact under a frictionless law has no tangential multiplier, so it
     * neither sticks nor slips: it has its own value.
     */
    namespace contact_status
    {
      /** No contact pressure (up to the status tolerance). */
      constexpr int separated = 0;
      /** In contact, tangential multiplier strictly inside the slip bound. */
      constexpr int stick = 1;
      /** In contact, tangential multiplier on the slip bound. */
      constexpr int slip = 2;
      /** In contact, frictionless pair (no tangential multiplier). */
      constexpr int frictionless_contact = 3;
      /**
       * A point of the written surface that is no contact node: a hanging
       * node (values interpolated from its parents) or a node beyond the
       * search distance.
       */
      constexpr int no_contact_node = -1;
    } // namespace contact_status


    /**
     * What the contact-surface file shows at one contact node (all in the
     * reference configuration, SI units; 2D: per metre of thickness).
     */
    template <int dim>
    struct ContactSurfaceNode
    {
      dealii::Point<dim> position;
      /** Unit normal, from the slave into the master [-]. */
      dealii::Tensor<1, dim> normal;
      /** lambda_N / w [Pa]: the normal contact pressure. */
      double pressure = 0;
      /** sum_k lambda_T,k t_k / w [Pa]: the tangential traction. */
      dealii::Tensor<1, dim> tangential_traction;
      /** sum_k (B_T u + o_T)_k t_k [m]: relative tangential displacement,
       *  accumulated over the load steps. */
      dealii::Tensor<1, dim> slip;
      /** The part of slip of the last load step [m] (the whole slip for
       *  a single step). */
      dealii::Tensor<1, dim> slip_increment;
      /** c - B_N u [m]: the gap after deformation (0 where in contact). */
      double gap = 0;
      /**
       * Contact area weight w = int phi ds over the slave surface [m^2; 2D:
       * m^2 per metre of thickness, i.e. m]: pressure * weight is the nodal
       * force lambda_N, and the w are the weights of the nodal quadrature on
       * the contact surface (e.g. for pressure errors against a closed form).
       */
      double weight = 0;
      /** A contact_status value: 0 separated, 1 stick, 2 slip, 3
       * frictionless contact. */
      int status = contact_status::separated;
    };


    /**
     * Write the slave surface @p mesh of one contact pair, with the values of
     * its contact @p nodes (in the pair's node order, as @p mesh refers to
     * them), as a VTK XML unstructured grid (.vtu, binary and zlib-compressed
     * like the body files, written by VTK's vtkXMLUnstructuredGridWriter):
     * line cells (2D) or quadrilaterals (3D), and the point fields
     *  - `pressure_Pa' p_i = lambda_N,i / w_i,
     *  - `normal_force_N' lambda_N,i = p_i w_i (2D: N per metre of thickness),
     *  - `area_weight_m2' w_i = int phi_i ds (2D: m^2 per metre, i.e. m),
     *  - `gap_m', `tangential_traction_Pa' (vector), `slip_m' (vector),
     *  - `status' (contact_status; -1 at a point that is no contact node),
     *  - `normal' (unit vector, slave into master),
     *  - `slip_increment_m' (vector): the slip of the last load step.
     * Vectors have three components (z = 0 in 2D), as VTK expects.  The
     * pressure is a nodal field: integrated over the cells with its linear
     * (2D) / bilinear (3D) interpolant it gives sum_i p_i int phi_i ds =
     * sum_i lambda_N,i for Q1 (lib/io/README.md: what ParaView's Integrate
     * Variables gives).  Points that are no contact nodes (status -1): a
     * hanging node gets its parents' values combined by the constraint
     * (weight and force 0: they went to the parents); a node beyond the
     * search distance gets pressure, traction, slip, weight and force 0 and
     * gap NaN (not computed).
     *
     * @p piece: write only the cells owned by that process
     * (ContactSurfaceMesh::owner()); numbers::invalid_unsigned_int: all.
     */
    template <int dim>
    void
    write_contact_surface(
      std::ostream                               &out,
      const ContactSurfaceMesh<dim>              &mesh,
      const std::vector<ContactSurfaceNode<dim>> &nodes,
      const unsigned int piece = dealii::numbers::invalid_unsigned_int);

    /**
     * The .pvtu record of the pieces @p pieces (file names) written by
     * write_contact_surface(): the fields' names, types and components.
     */
    void
    write_contact_surface_record(std::ostream                   &out,
                                 const std::vector<std::string> &pieces);

    /**
     * A PVD collection: each entry (time, file name) becomes a data set;
     * entries with equal time are parts of one step.
     */
    void
    write_pvd(std::ostream                                      &out,
              const std::vector<std::pair<double, std::string>> &entries);
  } // namespace io
} // namespace dualcontact
