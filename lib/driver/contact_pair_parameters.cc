#include <deal.II/base/exceptions.h>
#include <deal.II/base/patterns.h>
#include <deal.II/base/utilities.h>

#include <driver/contact_pair_parameters.h>

#include <io/parameter_file.h>

#include <algorithm>
#include <iomanip>
#include <limits>
#include <sstream>

namespace dualcontact
{
  namespace driver
  {
    namespace
    {
      std::vector<double>
      parse_doubles(const std::string &text)
      {
        return dealii::Utilities::string_to_double(
          dealii::Utilities::split_string_list(text));
      }

    } // namespace


    template <int dim>
    void
    ContactPairParameters<dim>::declare_parameters(
      dealii::ParameterHandler &prm)
    {
      prm.declare_entry("Slave body",
                        "1",
                        dealii::Patterns::Integer(1),
                        "The body (1, 2, ... as in `Body N') whose surface "
                        "carries the contact nodes.");
      prm.declare_entry("Slave boundary id",
                        "0",
                        dealii::Patterns::Integer(0, 65535),
                        "The boundary id of the slave body's faces that may "
                        "come into contact (ids refer to the mesh before "
                        "placement, as in `Dirichlet N').");
      prm.declare_entry("Master",
                        "obstacle 1",
                        dealii::Patterns::Anything(),
                        "What the slave surface touches: `obstacle K' (the "
                        "rigid `Obstacle K') or `body K' (the surface "
                        "`Master boundary id' of `Body K', another body; the "
                        "meshes need not match).");
      prm.declare_entry("Master boundary id",
                        "0",
                        dealii::Patterns::Integer(0, 65535),
                        "Master = body K: the boundary id of its faces that "
                        "the slave nodes are projected onto. Ignored for an "
                        "obstacle.");
      prm.declare_entry(
        "Friction law",
        "frictionless",
        dealii::Patterns::Selection(
          "frictionless|tresca|tresca orthotropic|coulomb|coulomb orthotropic"),
        "frictionless (Signorini: no penetration, no tangential traction); "
        "tresca (|tangential traction| <= `Slip bound'); tresca orthotropic "
        "(3D: tangential traction in the ellipse with semi-axes `Slip "
        "bounds' along the first and second tangent); coulomb (|tangential "
        "traction| <= `Friction coefficient' * pressure, solved as a fixed "
        "point over Tresca problems, see subsection `Coulomb'); coulomb "
        "orthotropic (3D: semi-axes `Friction coefficients' * pressure).");
      prm.declare_entry("Slip bound",
                        "0",
                        dealii::Patterns::Double(),
                        "tresca: the slip bound g [N/m^2] (> 0): the "
                        "tangential traction at which the surface slips.");
      prm.declare_entry("Slip bounds",
                        "0, 0",
                        dealii::Patterns::List(dealii::Patterns::Double(),
                                               2,
                                               2),
                        "tresca orthotropic: the slip bounds g1, g2 [N/m^2] "
                        "(both > 0) along the first and second tangent "
                        "direction.");
      prm.declare_entry("Friction coefficient",
                        "0",
                        dealii::Patterns::Double(),
                        "coulomb: the friction coefficient mu [-] (>= 0).");
      prm.declare_entry("Friction coefficients",
                        "0, 0",
                        dealii::Patterns::List(dealii::Patterns::Double(),
                                               2,
                                               2),
                        "coulomb orthotropic: the coefficients mu1, mu2 [-] "
                        "(both > 0) along the first and second tangent "
                        "direction.");
      prm.declare_entry("First tangent direction",
                        dim == 2 ? "1, 0" : "1, 0, 0",
                        dealii::Patterns::List(dealii::Patterns::Double(),
                                               dim,
                                               dim),
                        "3D: the first tangent of each contact node is the "
                        "projection of this direction [-] onto the node's "
                        "tangent plane (orthotropic laws refer to it; the "
                        "second tangent completes a right-handed frame). "
                        "Ignored in 2D, where the tangent is the normal "
                        "turned by 90 degrees.");
      prm.declare_entry("Search distance",
                        "0",
                        dealii::Patterns::Double(),
                        "Slave nodes farther than this from the master [m] "
                        "are not contact nodes (in small displacements they "
                        "cannot touch); 0 means no limit. Must be >= 0.");
      prm.declare_entry(
        "Discretization",
        "node to segment",
        dealii::Patterns::Selection("node to segment|mortar"),
        "How the slave surface is coupled to the master. node to segment: "
        "each slave node with its lumped weight int phi ds against the "
        "master's shape functions at its closest point (fails the contact "
        "patch test on non-matching meshes). mortar: dual mortar, the "
        "slave's biorthogonal basis integrated against the master over the "
        "slave faces cut by the projected master faces, weighted gaps and "
        "averaged slave normals, hanging slave nodes condensed into their "
        "parents' rows (passes the patch test to round-off; degree-1 faces "
        "and replicated meshes only).");
      prm.declare_entry("Mortar coverage",
                        "0.2",
                        dealii::Patterns::Double(0, 1),
                        "Discretization = mortar: slave nodes whose dual "
                        "basis function is covered by the master for less "
                        "than this fraction of its integral [-] (at and "
                        "beyond the master's edge) are not contact nodes: "
                        "their rows would divide by a small or negative "
                        "integral. A node on the master's edge has about "
                        "1/2 (2D) or 1/4 (3D corner).");
      prm.declare_entry("Penetration tolerance",
                        "0.25",
                        dealii::Patterns::Double(0),
                        "Deepest initial penetration of a slave node into "
                        "the master (a negative initial gap) allowed, "
                        "relative to the mesh size of the slave surface "
                        "[-]: deeper nodes stop the run before solving "
                        "(bodies that overlap, or a body behind its "
                        "obstacle). Faceted curved surfaces overlap by "
                        "about h^2 / (8 R), well below the default; raise "
                        "it for an intended interference fit.");
    }


    template <int dim>
    void
    ContactPairParameters<dim>::parse_parameters(
      dealii::ParameterHandler                   &prm,
      const std::string                          &path,
      const unsigned int                          n_bodies,
      const std::vector<ObstacleParameters<dim>> &obstacles)
    {
      path_     = path;
      pair      = contact::ContactPair<dim>();
      pair.name = path;

      const unsigned int slave = prm.get_integer("Slave body");
      AssertThrow(slave >= 1 && slave <= n_bodies,
                  dealii::ExcMessage(
                    "There is no body " + std::to_string(slave) +
                    " (the scene has " + std::to_string(n_bodies) + ") " +
                    io::parameter_location(path, "Slave body") + "."));
      pair.slave_body     = slave - 1;
      pair.slave_boundary = prm.get_integer("Slave boundary id");

      // Master: `obstacle K' or `body K'
      const std::string master_text =
        dealii::Utilities::trim(prm.get("Master"));
      std::istringstream master_stream(master_text);
      std::string        kind;
      long               index = 0;
      std::string        rest;
      master_stream >> kind >> index;
      const bool read_ok = !master_stream.fail();
      master_stream >> rest;
      AssertThrow(read_ok && rest.empty() &&
                    (kind == "obstacle" || kind == "body"),
                  dealii::ExcMessage(
                    "Cannot read `" + master_text + "' " +
                    io::parameter_location(path, "Master") +
                    ": expected `obstacle K' or `body K' with a number K."));
      master_description = kind + " " + std::to_string(index);
      if (kind == "obstacle")
      {
        AssertThrow(index >= 1 && index <= static_cast<long>(obstacles.size()),
                    dealii::ExcMessage(
                      "There is no obstacle " + std::to_string(index) +
                      " (the scene has " + std::to_string(obstacles.size()) +
                      "; see `set Number of obstacles') " +
                      io::parameter_location(path, "Master") + "."));
        pair.obstacle = obstacles[index - 1].obstacle;
      }
      else
      {
        AssertThrow(index >= 1 && index <= static_cast<long>(n_bodies),
                    dealii::ExcMessage(
                      "There is no body " + std::to_string(index) +
                      " (the scene has " + std::to_string(n_bodies) + ") " +
                      io::parameter_location(path, "Master") + "."));
        AssertThrow(static_cast<unsigned int>(index) != slave,
                    dealii::ExcMessage("The master body is the slave body " +
                                       io::parameter_location(path, "Master") +
                                       ": self-contact is not supported."));
        pair.master_body     = index - 1;
        pair.master_boundary = prm.get_integer("Master boundary id");
      }

      // friction law
      const std::string law = prm.get("Friction law");
      using Type            = contact::FrictionLaw::Type;
      const std::string law_location =
        io::parameter_location(path, "Friction law");
      if (law == "frictionless")
        pair.friction.type = Type::frictionless;
      else if (law == "tresca")
      {
        pair.friction.type  = Type::tresca_isotropic;
        pair.friction.first = prm.get_double("Slip bound");
        AssertThrow(pair.friction.first > 0,
                    dealii::ExcMessage(
                      "Friction law = tresca needs a slip bound > 0, got " +
                      prm.get("Slip bound") + " " +
                      io::parameter_location(path, "Slip bound") + "."));
      }
      else if (law == "coulomb")
      {
        pair.friction.type  = Type::coulomb_isotropic;
        pair.friction.first = prm.get_double("Friction coefficient");
        AssertThrow(pair.friction.first >= 0,
                    dealii::ExcMessage(
                      "Friction law = coulomb needs a friction coefficient "
                      ">= 0, got " +
                      prm.get("Friction coefficient") + " " +
                      io::parameter_location(path, "Friction coefficient") +
                      "."));
      }
      else
      {
        const bool        tresca = (law == "tresca orthotropic");
        const std::string entry =
          tresca ? "Slip bounds" : "Friction coefficients";
        AssertThrow(dim == 3,
                    dealii::ExcMessage(
                      "Friction law = " + law +
                      " needs two tangent directions, which exist in 3D "
                      "only (2D has one tangent: use " +
                      (tresca ? "tresca" : "coulomb") + ") " + law_location +
                      "."));
        const std::vector<double> values = parse_doubles(prm.get(entry));
        AssertThrow(values.size() == 2 && values[0] > 0 && values[1] > 0,
                    dealii::ExcMessage("Friction law = " + law +
                                       " needs two positive values, "
                                       "got `" +
                                       prm.get(entry) + "' " +
                                       io::parameter_location(path, entry) +
                                       "."));
        pair.friction.type =
          tresca ? Type::tresca_orthotropic : Type::coulomb_orthotropic;
        pair.friction.first  = values[0];
        pair.friction.second = values[1];
      }

      const std::vector<double> direction =
        parse_doubles(prm.get("First tangent direction"));
      double norm = 0;
      for (unsigned int d = 0; d < dim; ++d)
      {
        pair.first_tangent_direction[d] = direction[d];
        norm += direction[d] * direction[d];
      }
      AssertThrow(dim == 2 || norm > 0,
                  dealii::ExcMessage(
                    "The first tangent direction is zero " +
                    io::parameter_location(path, "First tangent direction") +
                    "."));

      const double search = prm.get_double("Search distance");
      AssertThrow(search >= 0,
                  dealii::ExcMessage(
                    "The search distance must be >= 0 (0: no limit), got " +
                    prm.get("Search distance") + " " +
                    io::parameter_location(path, "Search distance") + "."));
      pair.search_distance =
        search > 0 ? search : std::numeric_limits<double>::max();
      penetration_tolerance = prm.get_double("Penetration tolerance");
      pair.discretization =
        prm.get("Discretization") == "mortar" ?
          contact::ContactPair<dim>::Discretization::mortar :
          contact::ContactPair<dim>::Discretization::node_to_segment;
      pair.mortar_coverage = prm.get_double("Mortar coverage");
    }


    template <int dim>
    void
    ContactPairParameters<dim>::check_initial_penetration(
      const std::vector<contact::ContactNode<dim>> &nodes,
      const unsigned int                            pair_index,
      const double                                  mesh_size) const
    {
      const contact::ContactNode<dim> *deepest = nullptr;
      for (const auto &node : nodes)
        if (node.pair == pair_index &&
            (deepest == nullptr || node.gap < deepest->gap))
          deepest = &node;
      const double allowed = penetration_tolerance * mesh_size;
      if (deepest == nullptr || !(deepest->gap < -allowed))
        return;
      std::ostringstream message;
      message << std::setprecision(4) << pair.name << ": the slave node at ("
              << deepest->position << ") of Body " << pair.slave_body + 1
              << " lies " << -deepest->gap << " m inside its master ("
              << master_description << ", closest point ("
              << deepest->master_point
              << ")) before any load, deeper than the `Penetration "
                 "tolerance' "
              << penetration_tolerance << " times the slave mesh size "
              << mesh_size << " m = " << allowed << " m "
              << io::parameter_location(path_, "Penetration tolerance")
              << ": the bodies overlap (a body placed inside another, or "
                 "behind its obstacle). Move them apart (`subsection "
                 "Placement'), or raise the tolerance for an intended "
                 "interference fit.";
      AssertThrow(false, dealii::ExcMessage(message.str()));
    }


    template <int dim>
    void
    ContactPairParameters<dim>::check_mesh(
      const std::vector<std::shared_ptr<dealii::Triangulation<dim>>>
        &triangulations) const
    {
      const auto check = [&](const unsigned int               body,
                             const dealii::types::boundary_id id,
                             const std::string               &entry)
      {
        const std::vector<dealii::types::boundary_id> ids =
          triangulations[body]->get_boundary_ids();
        AssertThrow(std::find(ids.begin(), ids.end(), id) != ids.end(),
                    dealii::ExcMessage(
                      "The mesh of Body " + std::to_string(body + 1) +
                      " has no boundary id " + std::to_string(id) +
                      " (its boundary ids: " + io::join_numbers(ids) + ") " +
                      io::parameter_location(path_, entry) + "."));
      };
      check(pair.slave_body, pair.slave_boundary, "Slave boundary id");
      if (!pair.obstacle)
        check(pair.master_body, pair.master_boundary, "Master boundary id");
    }


    template <int dim>
    bool
    ContactPairParameters<dim>::involves_body(const unsigned int body) const
    {
      return pair.slave_body == body ||
             (!pair.obstacle && pair.master_body == body);
    }


    template class ContactPairParameters<2>;
    template class ContactPairParameters<3>;
  } // namespace driver
} // namespace dualcontact
