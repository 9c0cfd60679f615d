#include <deal.II/base/exceptions.h>
#include <deal.II/base/patterns.h>
#include <deal.II/base/utilities.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/manifold_lib.h>

#include <fem/cell_family.h>
#include <io/file_locator.h>
#include <io/mesh_check.h>
#include <io/mesh_generator.h>
#include <io/parameter_file.h>

#include <cmath>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <typeinfo>

namespace dualcontact
{
  namespace io
  {
    namespace
    {
      template <int dim>
      dealii::Point<dim>
      parse_point(const std::string &text)
      {
        const std::vector<double> values = dealii::Utilities::string_to_double(
          dealii::Utilities::split_string_list(text));
        dealii::Point<dim> point;
        for (unsigned int d = 0; d < dim; ++d)
          point[d] = values[d];
        return point;
      }
    } // namespace


    template <int dim>
    void
    MeshGenerator<dim>::declare_parameters(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection("Mesh");
      prm.declare_entry(
        "Generator",
        "box",
        dealii::Patterns::Selection(
          "box|ball|half ball|quarter ball|cylinder|gmsh"),
        "How the mesh is made. `box': a rectangle (2D) or box (3D) from "
        "`Lower corner' to `Upper corner' with `Subdivisions' cells per "
        "direction; boundary ids 0/1 at x = min/max, 2/3 at y = min/max, 4/5 "
        "at z = min/max. `ball': a disc (2D) or ball (3D) of `Radius' around "
        "the origin; boundary id 0. `half ball': the half x >= 0 of that disc "
        "or ball; boundary id 0 on the curved part, 1 on the cut x = 0. "
        "`quarter ball': the lower quarter disc x >= 0, y <= 0 (2D) or the "
        "lower octant x >= 0, y >= 0, z <= 0 (3D) of that ball, whose lowest "
        "point (0, -R) / (0, 0, -R) touches a plane below it (Hertz contact "
        "with symmetry planes); boundary id 0 on the curved part, 1 on the "
        "cut x = 0, 2 on the flat top y = 0 (2D) / z = 0 (3D), 3 on the cut "
        "y = 0 (3D). "
        "`cylinder' (3D): axis along x from -`Half length' to +`Half length', "
        "`Radius'; boundary id 0 on the hull, 1 at x = -L, 2 at x = +L (2D: "
        "the rectangle [-L, L] x [-R, R], id 0 at y = +-R). `gmsh': read "
        "`Gmsh file'; boundary ids are the physical tags of boundary "
        "lines/faces, material ids the physical tags of the cells. Generated "
        "meshes have material id 0. Ids refer to the mesh before placement.");
      prm.declare_entry(
        "Cell type",
        "hypercube",
        dealii::Patterns::Selection("hypercube|simplex"),
        "The cells of a generated mesh: `hypercube' (quadrilaterals in 2D, "
        "hexahedra in 3D) or `simplex' (triangles, tetrahedra): a box is "
        "split into 2 triangles / 5 tetrahedra per subdivision, the other "
        "generators' cells into 8 triangles / 24 tetrahedra, curved "
        "boundaries kept for refinement. The boundary ids are the same. "
        "`gmsh': the cells are those of the file, and `simplex' is refused "
        "for a file of quadrilaterals or hexahedra. Tetrahedral meshes "
        "cannot be refined locally (deal.II 9.4 has no hanging nodes on "
        "tetrahedra).");
      prm.declare_entry("Lower corner",
                        dim == 2 ? "0, 0" : "0, 0, 0",
                        dealii::Patterns::List(dealii::Patterns::Double(),
                                               dim,
                                               dim),
                        "box: the corner with the smallest coordinates [m] "
                        "(dim numbers).");
      prm.declare_entry("Upper corner",
                        dim == 2 ? "1, 1" : "1, 1, 1",
                        dealii::Patterns::List(dealii::Patterns::Double(),
                                               dim,
                                               dim),
                        "box: the corner with the largest coordinates [m] "
                        "(dim numbers).");
      prm.declare_entry("Subdivisions",
                        dim == 2 ? "1, 1" : "1, 1, 1",
                        dealii::Patterns::List(dealii::Patterns::Integer(1),
                                               dim,
                                               dim),
                        "box: number of cells per coordinate direction "
                        "(dim numbers) before global refinement.");
      prm.declare_entry("Radius",
                        "1",
                        dealii::Patterns::Double(0),
                        "ball, half ball, cylinder: radius [m] (> 0).");
      prm.declare_entry("Half length",
                        "1",
                        dealii::Patterns::Double(0),
                        "cylinder: half the length [m] along the axis (> 0).");
      prm.declare_entry(
        "Gmsh file",
        "",
        dealii::Patterns::Anything(),
        "gmsh: the mesh file (ASCII Gmsh format as read by deal.II; tested: "
        "2.2 and 4.1; quadrilaterals/hexahedra or triangles/tetrahedra, "
        "linear cells). A relative name is looked up relative to "
        "the working directory, then to the folder of this parameter file, "
        "then to the dualcontact source folder.");
      prm.declare_entry("Local refinements",
                        "0",
                        dealii::Patterns::Integer(0, 20),
                        "After the global refinements, this many times the "
                        "cells within `Local refinement radius' (plus one "
                        "cell diameter) of `Local refinement center' are "
                        "refined, e.g. towards a contact zone. Hanging "
                        "nodes are constrained.");
      prm.declare_entry("Local refinement center",
                        dim == 2 ? "0, 0" : "0, 0, 0",
                        dealii::Patterns::List(dealii::Patterns::Double(),
                                               dim,
                                               dim),
                        "The center of the local refinement [m] (dim "
                        "numbers, placed coordinates).");
      prm.declare_entry("Local refinement radius",
                        "0",
                        dealii::Patterns::Double(0),
                        "The radius of the local refinement [m] (>= 0).");
      prm.declare_entry("Global refinements",
                        "0",
                        dealii::Patterns::Integer(0, 12),
                        "Number of times every cell is refined (each "
                        "refinement splits a cell into 2^dim children).");
      prm.leave_subsection();
    }


    template <int dim>
    void
    MeshGenerator<dim>::parse_parameters(
      dealii::ParameterHandler &prm,
      const std::string        &parent_path,
      const std::string        &parameter_file_folder)
    {
      path_ = join_path(parent_path, "Mesh");
      prm.enter_subsection("Mesh");
      const std::string generator = prm.get("Generator");
      if (generator == "box")
        kind_ = Kind::box;
      else if (generator == "ball")
        kind_ = Kind::ball;
      else if (generator == "half ball")
        kind_ = Kind::half_ball;
      else if (generator == "quarter ball")
        kind_ = Kind::quarter_ball;
      else if (generator == "cylinder")
        kind_ = Kind::cylinder;
      else
        kind_ = Kind::gmsh;

      simplex_      = prm.get("Cell type") == "simplex";
      lower_corner_ = parse_point<dim>(prm.get("Lower corner"));
      upper_corner_ = parse_point<dim>(prm.get("Upper corner"));
      subdivisions_ = {};
      for (const int n : dealii::Utilities::string_to_int(
             dealii::Utilities::split_string_list(prm.get("Subdivisions"))))
        subdivisions_.push_back(n);
      radius_              = prm.get_double("Radius");
      half_length_         = prm.get_double("Half length");
      n_refinements_       = prm.get_integer("Global refinements");
      n_local_refinements_ = prm.get_integer("Local refinements");
      local_refinement_center_ =
        parse_point<dim>(prm.get("Local refinement center"));
      local_refinement_radius_ = prm.get_double("Local refinement radius");

      if (kind_ == Kind::box)
        for (unsigned int d = 0; d < dim; ++d)
          AssertThrow(upper_corner_[d] > lower_corner_[d],
                      dealii::ExcMessage(
                        "The upper corner of the box must be larger than "
                        "the lower corner in every coordinate " +
                        parameter_location(path_, "Upper corner") + "."));
      if (kind_ == Kind::ball || kind_ == Kind::half_ball ||
          kind_ == Kind::quarter_ball || kind_ == Kind::cylinder)
        AssertThrow(radius_ > 0,
                    dealii::ExcMessage("The radius must be positive " +
                                       parameter_location(path_, "Radius") +
                                       "."));
      if (kind_ == Kind::cylinder)
        AssertThrow(half_length_ > 0,
                    dealii::ExcMessage(
                      "The half length must be positive " +
                      parameter_location(path_, "Half length") + "."));
      AssertThrow(!(dim == 3 && simplex_ && n_local_refinements_ > 0),
                  dealii::ExcMessage(
                    "Tetrahedral meshes cannot be refined locally (deal.II "
                    "9.4 has no hanging nodes on tetrahedra) " +
                    parameter_location(path_, "Local refinements") +
                    " with `set Cell type = simplex'; refine globally (`set "
                    "Global refinements') or use hexahedra."));
      if (kind_ == Kind::gmsh)
        gmsh_file_ = locate_file(prm.get("Gmsh file"),
                                 parameter_file_folder,
                                 parameter_location(path_, "Gmsh file"));
      prm.leave_subsection();
    }


    template <int dim>
    void
    MeshGenerator<dim>::generate(dealii::Triangulation<dim> &triangulation,
                                 const std::string          &mesh_name) const
    {
      if (kind_ == Kind::gmsh || !simplex_)
      {
        generate_cells(triangulation, mesh_name);
        if (kind_ == Kind::gmsh && simplex_)
          AssertThrow(fem::CellFamily<dim>(triangulation,
                                           described_name(mesh_name))
                        .is_simplex(),
                      dealii::ExcMessage(
                        "The mesh file `" + gmsh_file_ + "' of " + mesh_name +
                        " has " +
                        fem::CellFamily<dim>(triangulation, mesh_name)
                          .cells_in_words() +
                        ", not the simplices asked for " +
                        parameter_location(path_, "Cell type") +
                        " (a Gmsh file's cells are those it holds: `set "
                        "Cell type = hypercube' or mesh it with triangles / "
                        "tetrahedra)."));
        return;
      }
      if (kind_ == Kind::box)
      {
        generate_simplex_box(triangulation);
        return;
      }
      // the hypercube mesh, its cells split; the curved boundaries keep
      // their manifolds: the id of each boundary id's faces is set again
      // on the split faces (and, in 3D, their edges)
      dealii::Triangulation<dim> hypercubes;
      generate_cells(hypercubes, mesh_name);
      std::map<dealii::types::boundary_id, dealii::types::manifold_id>
        manifold_of_boundary;
      for (const auto &face : hypercubes.active_face_iterators())
        if (face->at_boundary() &&
            face->manifold_id() != dealii::numbers::flat_manifold_id)
          manifold_of_boundary[face->boundary_id()] = face->manifold_id();
      dealii::GridGenerator::convert_hypercube_to_simplex_mesh(hypercubes,
                                                               triangulation);
      triangulation.set_all_manifold_ids(dealii::numbers::flat_manifold_id);
      for (const auto &face : triangulation.active_face_iterators())
        if (face->at_boundary())
          if (const auto it = manifold_of_boundary.find(face->boundary_id());
              it != manifold_of_boundary.end())
            face->set_all_manifold_ids(it->second);
      for (const auto &[boundary, manifold] : manifold_of_boundary)
        triangulation.set_manifold(manifold, hypercubes.get_manifold(manifold));
    }


    template <int dim>
    void
    MeshGenerator<dim>::generate_simplex_box(
      dealii::Triangulation<dim> &triangulation) const
    {
      dealii::GridGenerator::subdivided_hyper_rectangle_with_simplices(
        triangulation, subdivisions_, lower_corner_, upper_corner_);
      // the ids of subdivided_hyper_rectangle(colorize = true), from the
      // face centres: 2 d at x_d = min, 2 d + 1 at x_d = max
      for (const auto &face : triangulation.active_face_iterators())
        if (face->at_boundary())
        {
          const dealii::Point<dim> c = face->center();
          for (unsigned int d = 0; d < dim; ++d)
          {
            const double tolerance =
              1e-10 * (upper_corner_[d] - lower_corner_[d]);
            if (std::abs(c[d] - lower_corner_[d]) < tolerance)
              face->set_boundary_id(2 * d);
            else if (std::abs(c[d] - upper_corner_[d]) < tolerance)
              face->set_boundary_id(2 * d + 1);
          }
        }
    }


    template <int dim>
    void
    MeshGenerator<dim>::generate_cells(
      dealii::Triangulation<dim> &triangulation,
      const std::string          &mesh_name) const
    {
      switch (kind_)
      {
        case Kind::box:
          dealii::GridGenerator::subdivided_hyper_rectangle(
            triangulation, subdivisions_, lower_corner_, upper_corner_, true);
          break;
        case Kind::ball:
          dealii::GridGenerator::hyper_ball(triangulation,
                                            dealii::Point<dim>(),
                                            radius_);
          break;
        case Kind::half_ball:
          dealii::GridGenerator::half_hyper_ball(triangulation,
                                                 dealii::Point<dim>(),
                                                 radius_);
          break;
        case Kind::quarter_ball:
        {
          // deal.II's quarter_hyper_ball is the first quadrant/octant;
          // rotate it below the centre: (x, y) -> (y, -x) in 2D, (x, y, z)
          // -> (y, x, -z) in 3D (a rotation by 180 degrees about (1, 1, 0)),
          // both orientation-preserving, so the cells stay valid
          dealii::GridGenerator::quarter_hyper_ball(triangulation,
                                                    dealii::Point<dim>(),
                                                    radius_);
          dealii::GridTools::transform(
            [](const dealii::Point<dim> &p)
            {
              dealii::Point<dim> q;
              if constexpr (dim == 2)
              {
                q[0] = p[1];
                q[1] = -p[0];
              }
              else
              {
                q[0] = p[1];
                q[1] = p[0];
                q[2] = -p[2];
              }
              return q;
            },
            triangulation);
          triangulation.set_all_manifold_ids(dealii::numbers::flat_manifold_id);
          const double tolerance = 1e-10 * radius_;
          for (const auto &cell : triangulation.active_cell_iterators())
            for (const unsigned int f : cell->face_indices())
              if (cell->face(f)->at_boundary())
              {
                const dealii::Point<dim> c = cell->face(f)->center();
                if (std::abs(c[0]) < tolerance)
                  cell->face(f)->set_boundary_id(1);
                else if (std::abs(c[dim - 1]) < tolerance)
                  cell->face(f)->set_boundary_id(2);
                else if (dim == 3 && std::abs(c[1]) < tolerance)
                  cell->face(f)->set_boundary_id(3);
                else
                {
                  cell->face(f)->set_boundary_id(0);
                  cell->face(f)->set_all_manifold_ids(0);
                }
              }
          triangulation.set_manifold(
            0, dealii::SphericalManifold<dim>(dealii::Point<dim>()));
          break;
        }
        case Kind::cylinder:
          dealii::GridGenerator::cylinder(triangulation, radius_, half_length_);
          break;
        case Kind::gmsh:
        {
          std::ifstream in(gmsh_file_);
          AssertThrow(in,
                      dealii::ExcMessage(
                        "Cannot open the mesh file `" + gmsh_file_ + "' " +
                        parameter_location(path_, "Gmsh file") + "."));
          dealii::GridIn<dim> grid_in;
          grid_in.attach_triangulation(triangulation);
          try
          {
            grid_in.read_msh(in);
          }
          catch (const dealii::ExceptionBase &exception)
          {
            std::ostringstream info;
            exception.print_info(info);
            AssertThrow(false,
                        dealii::ExcMessage(
                          "Cannot read the mesh file `" + gmsh_file_ + "' of " +
                          mesh_name + " " +
                          parameter_location(path_, "Gmsh file") + ": " +
                          dealii::Utilities::trim(info.str())));
          }
          AssertThrow(triangulation.n_active_cells() > 0,
                      dealii::ExcMessage("The mesh file `" + gmsh_file_ +
                                         "' of " + mesh_name +
                                         " has no cells."));
          break;
        }
      }
    }


    template <int dim>
    std::string
    MeshGenerator<dim>::described_name(const std::string &mesh_name) const
    {
      return mesh_name +
             (kind_ == Kind::gmsh ? " (file `" + gmsh_file_ + "')" : "");
    }


    template <int dim>
    double
    MeshGenerator<dim>::estimated_cells(const std::string &mesh_name) const
    {
      double coarse_cells = 1, volume = 1;
      if (kind_ == Kind::box)
      {
        for (unsigned int d = 0; d < dim; ++d)
        {
          coarse_cells *= subdivisions_[d];
          volume *= upper_corner_[d] - lower_corner_[d];
        }
        if (simplex_)
          coarse_cells *= dim == 2 ? 2 : 5;
      }
      else
      {
        dealii::Triangulation<dim> coarse;
        generate(coarse, mesh_name);
        coarse_cells = coarse.n_active_cells();
        // the volume needs cells deal.II can map (create() checks the same)
        check_cells(coarse, described_name(mesh_name));
        // GridTools::volume has no rule for simplices in deal.II 9.4
        volume = 0;
        for (const auto &cell : coarse.active_cell_iterators())
          volume += cell->measure();
      }
      const double global_cells =
        coarse_cells * std::pow(2., dim * double(n_refinements_));
      if (n_local_refinements_ == 0 || !(local_refinement_radius_ > 0))
        return global_cells;

      // Local refinements refine the ball of `Local refinement radius' once
      // more per step, so its cells end 2^steps smaller than the mean cell
      // after the global refinements.  Only the part of the ball inside the
      // body is meshed, and its centre may lie on the boundary (a contact
      // point): 1/2^dim of the ball is counted, a lower bound that never
      // refuses a mesh that fits but grows like 2^(dim steps) as the mesh
      // does.
      const double r    = local_refinement_radius_;
      const double ball = dim == 2 ? M_PI * r * r : 4. / 3. * M_PI * r * r * r;
      const double refined_volume = std::min(ball / std::pow(2., dim), volume);
      const double refined_cell_volume =
        volume / global_cells *
        std::pow(2., -dim * double(n_local_refinements_));
      return global_cells + refined_volume / refined_cell_volume;
    }


    template <int dim>
    std::string
    MeshGenerator<dim>::size_parameters() const
    {
      return "(" +
             std::string(kind_ == Kind::box ? "`set Subdivisions', " : "") +
             "`set Global refinements' and `set Local refinements' in "
             "`subsection " +
             path_ + "')";
    }


    template <int dim>
    void
    MeshGenerator<dim>::place(dealii::Triangulation<dim> &triangulation,
                              const Placement<dim>       &placement) const
    {
      if (placement.is_identity())
        return;
      dealii::GridTools::transform([&placement](const dealii::Point<dim> &point)
                                   { return placement(point); },
                                   triangulation);

      // The generators attach manifolds in the unplaced coordinates; replace
      // them by placed ones.  Curved ones first: a transfinite interpolation
      // is built from the manifolds of the boundary.
      const dealii::Point<dim> center = placement(dealii::Point<dim>());
      std::vector<dealii::types::manifold_id> transfinite;
      for (const auto id : triangulation.get_manifold_ids())
      {
        if (id == dealii::numbers::flat_manifold_id)
          continue;
        const auto &manifold = triangulation.get_manifold(id);
        if (dynamic_cast<const dealii::FlatManifold<dim> *>(&manifold))
          continue;
        if (dynamic_cast<const dealii::SphericalManifold<dim> *>(&manifold))
          triangulation.set_manifold(id,
                                     dealii::SphericalManifold<dim>(center));
        else if (dynamic_cast<
                   const dealii::TransfiniteInterpolationManifold<dim> *>(
                   &manifold))
          transfinite.push_back(id);
        else if constexpr (dim == 3)
        {
          if (dynamic_cast<const dealii::CylindricalManifold<dim> *>(&manifold))
          {
            dealii::Tensor<1, dim> axis;
            axis[0] = 1;
            triangulation.set_manifold(
              id,
              dealii::CylindricalManifold<dim>(placement.rotate(axis), center));
          }
          else
            AssertThrow(false,
                        dealii::ExcMessage(std::string("cannot place the "
                                                       "manifold ") +
                                           typeid(manifold).name()));
        }
        else
          AssertThrow(false,
                      dealii::ExcMessage(std::string("cannot place the "
                                                     "manifold ") +
                                         typeid(manifold).name()));
      }
      for (const auto id : transfinite)
      {
        dealii::TransfiniteInterpolationManifold<dim> manifold;
        manifold.initialize(triangulation);
        triangulation.set_manifold(id, manifold);
      }
    }


    template <int dim>
    void
    MeshGenerator<dim>::create(dealii::Triangulation<dim> &triangulation,
                               const Placement<dim>       &placement,
                               const std::string          &mesh_name) const
    {
      generate(triangulation, mesh_name);
      if (kind_ != Kind::gmsh)
        // colorized generators may number cells by position: one material
        for (const auto &cell : triangulation.active_cell_iterators())
          cell->set_material_id(0);
      check_cells(triangulation, described_name(mesh_name));
      place(triangulation, placement);
      AssertThrow(
        !(dim == 3 && n_local_refinements_ > 0 &&
          fem::CellFamily<dim>(triangulation, mesh_name).is_simplex()),
        dealii::ExcMessage(
          "The mesh of " + described_name(mesh_name) +
          " has tetrahedra, which cannot be refined locally (deal.II 9.4 has "
          "no hanging nodes on tetrahedra) " +
          parameter_location(path_, "Local refinements") +
          "; refine globally (`set Global refinements') or use hexahedra."));
      triangulation.refine_global(n_refinements_);
      for (unsigned int step = 0; step < n_local_refinements_; ++step)
      {
        for (const auto &cell : triangulation.active_cell_iterators())
          if (cell->center().distance(local_refinement_center_) <
              local_refinement_radius_ + cell->diameter())
            cell->set_refine_flag();
        triangulation.execute_coarsening_and_refinement();
      }
    }


    template <int dim>
    std::string
    MeshGenerator<dim>::description() const
    {
      std::ostringstream text;
      switch (kind_)
      {
        case Kind::box:
          text << (dim == 2 ? "rectangle " : "box ");
          for (unsigned int d = 0; d < dim; ++d)
            text << (d == 0 ? "" : " x ") << subdivisions_[d];
          break;
        case Kind::ball:
          text << (dim == 2 ? "disc" : "ball") << " of radius " << radius_;
          break;
        case Kind::half_ball:
          text << (dim == 2 ? "half disc" : "half ball") << " of radius "
               << radius_;
          break;
        case Kind::quarter_ball:
          text << (dim == 2 ? "quarter disc" : "octant of a ball")
               << " of radius " << radius_;
          break;
        case Kind::cylinder:
          text << "cylinder of radius " << radius_ << ", length "
               << 2 * half_length_;
          break;
        case Kind::gmsh:
          text << "Gmsh file " << gmsh_file_;
          break;
      }
      if (simplex_ && kind_ != Kind::gmsh)
        text << (dim == 2 ? " of triangles" : " of tetrahedra");
      text << ", " << n_refinements_ << " global refinement"
           << (n_refinements_ == 1 ? "" : "s");
      if (n_local_refinements_ > 0)
        text << ", " << n_local_refinements_ << " local refinement"
             << (n_local_refinements_ == 1 ? "" : "s") << " within "
             << local_refinement_radius_ << " m";
      return text.str();
    }


    template <int dim>
    const std::string &
    MeshGenerator<dim>::parameter_path() const
    {
      return path_;
    }


    template class MeshGenerator<2>;
    template class MeshGenerator<3>;
  } // namespace io
} // namespace dualcontact
