#include <deal.II/base/exceptions.h>

#include <fclib/fclib_file.h>
#include <fclib/scene_export.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <unistd.h>

namespace dualcontact
{
  namespace fclib
  {
    template <int dim>
    GlobalProblem
    make_global_problem(
      const std::vector<const fem::ElasticBody<dim> *> &bodies,
      const contact::ContactDiscretization<dim>        &contact,
      const contact::DualProblem<dim>                  &dual,
      const std::string                                &title)
    {
      for (const auto &pair : contact.pairs())
      {
        const auto &law = pair.friction;
        AssertThrow(law.type == contact::FrictionLaw::Type::frictionless ||
                      law.type == contact::FrictionLaw::Type::coulomb_isotropic,
                    dealii::ExcMessage(
                      "FCLIB export: contact pair `" + pair.name +
                      "' has Tresca or orthotropic friction; FCLIB problems "
                      "hold isotropic Coulomb friction only (frictionless "
                      "pairs are written with mu = 0)"));
      }
      AssertThrow(dual.n_rigid_body_modes() == 0,
                  dealii::ExcMessage(
                    "FCLIB export: a body of the scene has rigid-body modes "
                    "(no Dirichlet condition holds it), so K is singular and "
                    "the contact problem is not a FCLIB problem (it needs the "
                    "equality constraints of SMALSE-M)"));

      const std::vector<unsigned int> kept  = exported_nodes(contact);
      const unsigned int              n     = contact.n_dofs();
      const unsigned int              nodes = kept.size();
      const unsigned int              m     = dim * nodes;

      Triplets               M(n, n);
      dealii::Vector<double> f(n);
      for (unsigned int b = 0; b < bodies.size(); ++b)
      {
        const auto &K      = bodies[b]->stiffness_matrix();
        const auto  offset = contact.body_offset(b);
        for (unsigned int i = 0; i < K.m(); ++i)
          for (auto it = K.begin(i); it != K.end(i); ++it)
            if (it->value() != 0.)
              M.add(offset + i, offset + it->column(), it->value());
        const auto &load = bodies[b]->load_vector();
        for (unsigned int i = 0; i < load.size(); ++i)
          f(offset + i) = load(i);
      }

      Triplets    H(n, m);
      const auto &BN = contact.normal_matrix();
      const auto &BT = contact.tangential_matrix();
      for (unsigned int j = 0; j < nodes; ++j)
      {
        const unsigned int i = kept[j];
        for (auto it = BN.begin(i); it != BN.end(i); ++it)
          if (it->value() != 0.)
            H.add(it->column(), dim * j, -it->value());
        for (unsigned int k = 0; k < dim - 1; ++k)
        {
          const unsigned int row = (dim - 1) * i + k;
          for (auto it = BT.begin(row); it != BT.end(row); ++it)
            if (it->value() != 0.)
              H.add(it->column(), dim * j + 1 + k, -it->value());
        }
      }

      dealii::Vector<double>       w(m);
      const dealii::Vector<double> c = contact.normal_bound();
      std::vector<double>          mu(nodes, 0.);
      for (unsigned int i = 0; i < nodes; ++i)
      {
        w(dim * i) = c(i);
        for (unsigned int k = 0; k < dim - 1; ++k)
          w(dim * i + 1 + k) = -contact.tangential_offset()((dim - 1) * i + k);
        const auto &law = contact.pairs()[contact.nodes()[i].pair].friction;
        if (law.is_coulomb())
          mu[i] = law.first;
      }
      return GlobalProblem(dim, M, H, f, w, mu, title);
    }


    template <int dim>
    std::vector<unsigned int>
    exported_nodes(const contact::ContactDiscretization<dim> &contact)
    {
      std::vector<unsigned int> kept;
      const auto               &BN = contact.normal_matrix();
      for (unsigned int i = 0; i < contact.n_nodes(); ++i)
        for (auto it = BN.begin(i); it != BN.end(i); ++it)
          if (it->value() != 0.)
          {
            kept.push_back(i);
            break;
          }
      return kept;
    }


    template <int dim>
    dealii::Vector<double>
    to_fclib_layout(const contact::ContactDiscretization<dim> &contact,
                    const contact::DualProblem<dim>           &dual,
                    const dealii::Vector<double>              &lambda)
    {
      const unsigned int nodes = dual.n_contact_nodes();
      AssertThrow(lambda.size() == dual.n_multipliers(),
                  dealii::ExcMessage("to_fclib_layout: wrong size"));
      const std::vector<unsigned int> kept = exported_nodes(contact);
      dealii::Vector<double>          r(dim * kept.size());
      for (unsigned int j = 0; j < kept.size(); ++j)
      {
        const unsigned int i = kept[j];
        r(dim * j)           = lambda(i);
        const int fi         = dual.frictional_index(i);
        if (fi >= 0)
          for (unsigned int k = 0; k < dim - 1; ++k)
            r(dim * j + 1 + k) = lambda(nodes + (dim - 1) * fi + k);
      }
      return r;
    }


    template <int dim>
    dealii::Vector<double>
    to_dual_layout(const contact::ContactDiscretization<dim> &contact,
                   const contact::DualProblem<dim>           &dual,
                   const dealii::Vector<double>              &r)
    {
      const unsigned int              nodes = dual.n_contact_nodes();
      const std::vector<unsigned int> kept  = exported_nodes(contact);
      AssertThrow(r.size() == dim * kept.size(),
                  dealii::ExcMessage("to_dual_layout: wrong size"));
      dealii::Vector<double> lambda(dual.n_multipliers());
      for (unsigned int j = 0; j < kept.size(); ++j)
      {
        const unsigned int i = kept[j];
        lambda(i)            = r(dim * j);
        const int fi         = dual.frictional_index(i);
        if (fi >= 0)
          for (unsigned int k = 0; k < dim - 1; ++k)
            lambda(nodes + (dim - 1) * fi + k) = r(dim * j + 1 + k);
      }
      return lambda;
    }


    namespace
    {
      /** Let @p write make a file by path, then copy it into @p folder. */
      void
      write_through_temporary(
        io::OutputFolder                               &folder,
        const std::string                              &name,
        const std::function<void(const std::string &)> &write)
      {
        const std::filesystem::path temporary =
          std::filesystem::temp_directory_path() /
          ("dualcontact_" + std::to_string(getpid()) + "_" + name);
        try
        {
          write(temporary.string());
          folder.write(name,
                       [&](std::ostream &out)
                       {
                         std::ifstream in(temporary, std::ios::binary);
                         AssertThrow(in.good(),
                                     dealii::ExcMessage(
                                       "Cannot read back the temporary "
                                       "FCLIB file `" +
                                       temporary.string() + "'"));
                         out << in.rdbuf();
                       });
        }
        catch (...)
        {
          std::error_code error;
          std::filesystem::remove(temporary, error);
          throw;
        }
        std::error_code error;
        std::filesystem::remove(temporary, error);
      }
    } // namespace


    template <int dim>
    void
    write_scene_problem(
      io::OutputFolder                                 &folder,
      const ExportForm                                  form,
      const std::vector<const fem::ElasticBody<dim> *> &bodies,
      const contact::ContactDiscretization<dim>        &contact,
      const contact::DualProblem<dim>                  &dual,
      const dealii::Vector<double>                     &lambda,
      const std::string                                &title)
    {
      if (form == ExportForm::none)
        return;
      const GlobalProblem global =
        make_global_problem<dim>(bodies, contact, dual, title);
      // an empty lambda: no solution to store
      const dealii::Vector<double> r =
        lambda.size() > 0 ? to_fclib_layout(contact, dual, lambda) :
                            dealii::Vector<double>();
      const std::string description =
        "written by dualcontact " DUALCONTACT_VERSION
        "; unknowns per contact node [normal, tangents] in the node's frame; "
        "r = nodal contact forces [N], u = gap after deformation and minus "
        "the slip [m]; M = K, H = -B', w = [gap - prescribed normal "
        "displacement; -prescribed tangential displacement]";
      if (form == ExportForm::global || form == ExportForm::both)
        write_through_temporary(folder,
                                "contact_problem_global.hdf5",
                                [&](const std::string &path) {
                                  write_global(path, global, r, description);
                                });
      if (form == ExportForm::local || form == ExportForm::both)
      {
        const LocalProblem local = global.reduce_to_local();
        write_through_temporary(folder,
                                "contact_problem_local.hdf5",
                                [&](const std::string &path)
                                { write_local(path, local, r, description); });
      }
    }


    template void
    write_scene_problem<2>(io::OutputFolder &,
                           const ExportForm,
                           const std::vector<const fem::ElasticBody<2> *> &,
                           const contact::ContactDiscretization<2> &,
                           const contact::DualProblem<2> &,
                           const dealii::Vector<double> &,
                           const std::string &);
    template void
    write_scene_problem<3>(io::OutputFolder &,
                           const ExportForm,
                           const std::vector<const fem::ElasticBody<3> *> &,
                           const contact::ContactDiscretization<3> &,
                           const contact::DualProblem<3> &,
                           const dealii::Vector<double> &,
                           const std::string &);
    template GlobalProblem
    make_global_problem<2>(const std::vector<const fem::ElasticBody<2> *> &,
                           const contact::ContactDiscretization<2> &,
                           const contact::DualProblem<2> &,
                           const std::string &);
    template GlobalProblem
    make_global_problem<3>(const std::vector<const fem::ElasticBody<3> *> &,
                           const contact::ContactDiscretization<3> &,
                           const contact::DualProblem<3> &,
                           const std::string &);
    template std::vector<unsigned int>
    exported_nodes<2>(const contact::ContactDiscretization<2> &);
    template std::vector<unsigned int>
    exported_nodes<3>(const contact::ContactDiscretization<3> &);
    template dealii::Vector<double>
    to_fclib_layout<2>(const contact::ContactDiscretization<2> &,
                       const contact::DualProblem<2> &,
                       const dealii::Vector<double> &);
    template dealii::Vector<double>
    to_fclib_layout<3>(const contact::ContactDiscretization<3> &,
                       const contact::DualProblem<3> &,
                       const dealii::Vector<double> &);
    template dealii::Vector<double>
    to_dual_layout<2>(const contact::ContactDiscretization<2> &,
                      const contact::DualProblem<2> &,
                      const dealii::Vector<double> &);
    template dealii::Vector<double>
    to_dual_layout<3>(const contact::ContactDiscretization<3> &,
                      const contact::DualProblem<3> &,
                      const dealii::Vector<double> &);
  } // namespace fclib
} // namespace dualcontact
