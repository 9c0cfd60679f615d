#include <deal.II/base/exceptions.h>

#include <fclib/fclib_file.h>
#include <fclib/file_layout.h>
#include <fclib/libfclib_call.h>
#include <fclib/silent_hdf5_errors.h>

#include <hdf5.h>

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

extern "C"
{
#include <fclib.h>
}

namespace dualcontact
{
  namespace fclib
  {
    namespace
    {
      /** Triplets of an FCLIB matrix in any of its three storages. */
      Triplets
      to_triplets(const fclib_matrix &A, const std::string &what)
      {
        AssertThrow(A.m >= 0 && A.n >= 0,
                    dealii::ExcMessage(what + ": negative matrix size"));
        Triplets t(A.m, A.n);
        try
        {
          if (A.nz >= 0) // triplets: i row, p column (see the header)
            for (int k = 0; k < A.nz; ++k)
              t.add(A.i[k], A.p[k], A.x[k]);
          else if (A.nz == -1) // compressed columns
          {
            check_compressed_pointers(A.p, A.n + 1, A.nzmax, "column pointers");
            for (int j = 0; j < A.n; ++j)
              for (int k = A.p[j]; k < A.p[j + 1]; ++k)
                t.add(A.i[k], j, A.x[k]);
          }
          else if (A.nz == -2) // compressed rows
          {
            check_compressed_pointers(A.p, A.m + 1, A.nzmax, "row pointers");
            for (int r = 0; r < A.m; ++r)
              for (int k = A.p[r]; k < A.p[r + 1]; ++k)
                t.add(r, A.i[k], A.x[k]);
          }
          else
            AssertThrow(false,
                        dealii::ExcMessage("unknown storage nz = " +
                                           std::to_string(A.nz)));
        }
        catch (const dealii::ExceptionBase &e)
        {
          AssertThrow(false,
                      dealii::ExcMessage(what + ": " + exception_message(e)));
        }
        return t;
      }


      /** An FCLIB matrix (compressed columns) owning its arrays. */
      struct CscMatrix
      {
        explicit CscMatrix(const dealii::SparseMatrix<double> &A)
        {
          const unsigned int                                        n = A.n();
          std::vector<std::vector<std::pair<unsigned int, double>>> cols(n);
          for (unsigned int r = 0; r < A.m(); ++r)
            for (auto it = A.begin(r); it != A.end(r); ++it)
              if (it->value() != 0.)
                cols[it->column()].emplace_back(r, it->value());
          p.push_back(0);
          for (unsigned int j = 0; j < n; ++j)
          {
            for (const auto &[r, v] : cols[j])
            {
              i.push_back(r);
              x.push_back(v);
            }
            p.push_back(i.size());
          }
          if (i.empty()) // HDF5 cannot write empty data sets
          {
            i.push_back(0);
            x.push_back(0.);
            p.back() = 1;
            for (auto &v : p)
              v = (&v == &p.front()) ? 0 : 1;
          }
          matrix.nzmax = x.size();
          matrix.m     = A.m();
          matrix.n     = n;
          matrix.p     = p.data();
          matrix.i     = i.data();
          matrix.x     = x.data();
          matrix.nz    = -1;
          matrix.info  = nullptr;
        }
        std::vector<int>    p, i;
        std::vector<double> x;
        fclib_matrix        matrix;
      };


      /** The title/description strings of an FCLIB info record. */
      struct Info
      {
        Info(const std::string &t, const std::string &d, const std::string &m)
            : title(t)
            , description(d)
            , math(m)
        {
          info.title       = title.data();
          info.description = description.data();
          info.math_info   = math.data();
        }
        std::string title, description, math;
        fclib_info  info;
      };


      std::string
      title_of(const fclib_info *info)
      {
        return (info && info->title) ? std::string(info->title) : "";
      }


      void
      check_is_form(const std::string &path, const Form expected)
      {
        const Form form = form_of(path);
        AssertThrow(form == expected,
                    dealii::ExcMessage("FCLIB file `" + path + "' holds a " +
                                       to_string(form) + " problem, not a " +
                                       to_string(expected) + " one"));
      }


      /**
       * Calls @p make (which builds a problem from data read from @p path)
       * and puts the file's name in front of any message it throws.
       */
      template <typename Make>
      auto
      in_file(const std::string &path, const Make &make) -> decltype(make())
      {
        try
        {
          return make();
        }
        catch (const dealii::ExceptionBase &e)
        {
          AssertThrow(false,
                      dealii::ExcMessage("FCLIB file `" + path +
                                         "': " + exception_message(e)));
        }
        return {};
      }


      void
      check_dimension(const std::string &path, const int spacedim)
      {
        AssertThrow(spacedim == 2 || spacedim == 3,
                    dealii::ExcMessage("FCLIB file `" + path +
                                       "': space dimension " +
                                       std::to_string(spacedim)));
      }


      /** Throws naming @p path and the cause unless libfclib wrote it. */
      void
      check_written(const int status, const std::string &path)
      {
        const int error_number = errno;
        AssertThrow(status == 1,
                    dealii::ExcMessage(
                      "Cannot write the FCLIB file `" + path +
                      "': " + write_failure_cause(path, error_number)));
      }


      /**
       * /solution with r, u (and v for the global form) into @p temporary,
       * which becomes @p path.
       */
      void
      write_solution(const std::string            &path,
                     const std::string            &temporary,
                     const dealii::Vector<double> &r,
                     const dealii::Vector<double> &u,
                     const dealii::Vector<double> *v = nullptr)
      {
        std::vector<double> rr(r.begin(), r.end()), uu(u.begin(), u.end()), vv;
        if (v)
          vv.assign(v->begin(), v->end());
        fclib_solution solution{};
        solution.v = v ? vv.data() : nullptr;
        solution.r = rr.data();
        solution.u = uu.data();
        check_written(fclib_write_solution(&solution, temporary.c_str()), path);
      }


      /**
       * A file written under a temporary name beside @p path (with the
       * process id, so that two writers do not meet) and renamed to @p path
       * by commit(): the existing file stays intact until the new one is
       * complete, and a failed write removes the temporary file.
       */
      class TemporaryFile
      {
      public:
        explicit TemporaryFile(const std::string &path)
            : path_(path)
            , temporary_(path + "." + std::to_string(getpid()) + ".tmp")
        {
        }
        ~TemporaryFile()
        {
          std::error_code error;
          if (!committed_)
            std::filesystem::remove(temporary_, error);
        }
        const std::string &
        name() const
        {
          return temporary_;
        }
        void
        commit()
        {
          std::error_code error;
          std::filesystem::rename(temporary_, path_, error);
          AssertThrow(!error,
                      dealii::ExcMessage("Cannot rename `" + temporary_ +
                                         "' to `" + path_ +
                                         "': " + error.message()));
          committed_ = true;
        }

      private:
        std::string path_;
        std::string temporary_;
        bool        committed_ = false;
      };


      void
      remove_existing(const std::string &path)
      {
        std::error_code error;
        std::filesystem::remove(path, error);
        errno = 0;
        std::ofstream probe(path);
        AssertThrow(probe.good(),
                    dealii::ExcMessage(
                      "Cannot write the FCLIB file `" + path + "': " +
                      (errno != 0 ? std::string(std::strerror(errno)) :
                                    std::string("cause unknown"))));
        probe.close();
        std::filesystem::remove(path, error);
      }
    } // namespace


    std::string
    exception_message(const dealii::ExceptionBase &e)
    {
      std::ostringstream info;
      e.print_info(info);
      std::string text = info.str();
      // ExcMessage prints "    The violated condition was: ... Additional
      // information: <text>" in some versions; keep the text only
      const std::string marker = "Additional information:";
      const auto        at     = text.find(marker);
      if (at != std::string::npos)
        text = text.substr(at + marker.size());
      const auto first = text.find_first_not_of(" \n\t");
      const auto last  = text.find_last_not_of(" \n\t");
      return first == std::string::npos ? "" :
                                          text.substr(first, last - first + 1);
    }


    std::string
    to_string(const Form form)
    {
      return form == Form::local ? "local" : "global";
    }


    Form
    form_of(const std::string &path)
    {
      AssertThrow(std::ifstream(path).good(),
                  dealii::ExcMessage("Cannot open the FCLIB file `" + path +
                                     "'"));
      // HDF5 prints its error stack for failed calls: silence it, the
      // message here says what went wrong
      const SilentHdf5Errors silent;
      const htri_t           is_hdf5 = H5Fis_hdf5(path.c_str());
      int                    found   = -1;
      bool                   opened  = false;
      if (is_hdf5 > 0)
      {
        const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
        if (file >= 0)
        {
          opened = true;
          if (H5Lexists(file, "/fclib_local", H5P_DEFAULT) > 0)
            found = 0;
          else if (H5Lexists(file, "/fclib_global", H5P_DEFAULT) > 0)
            found = 1;
          H5Fclose(file);
        }
      }
      AssertThrow(is_hdf5 > 0,
                  dealii::ExcMessage("`" + path + "' is not an HDF5 file"));
      // the signature is there but HDF5 cannot open it: a file cut short
      // (an interrupted copy or write) or damaged
      AssertThrow(opened,
                  dealii::ExcMessage("`" + path +
                                     "' is a truncated or corrupt HDF5 file "
                                     "(HDF5 cannot open it)"));
      AssertThrow(found >= 0,
                  dealii::ExcMessage(
                    "`" + path +
                    "' holds neither /fclib_local nor /fclib_global: not an "
                    "FCLIB problem"));
      return found == 0 ? Form::local : Form::global;
    }


    LocalProblem
    read_local(const std::string &path, const Storage storage)
    {
      check_is_form(path, Form::local);
      // before libfclib allocates from the headers (see FileLayout)
      const FileLayout layout(path, Form::local);
      std::unique_ptr<fclib_local, void (*)(fclib_local *)> p(
        nullptr, fclib_delete_local);
      {
        const LibfclibCall call(path, "read");
        p.reset(fclib_read_local(path.c_str()));
      }
      AssertThrow(p && p->W && p->q && p->mu,
                  dealii::ExcMessage("libfclib could not read the local "
                                     "problem in `" +
                                     path + "'"));
      check_dimension(path, p->spacedim);
      const unsigned int n = p->W->m, nc = n / p->spacedim;
      AssertThrow(n % p->spacedim == 0,
                  dealii::ExcMessage("FCLIB file `" + path + "': W has " +
                                     std::to_string(n) +
                                     " rows, not a multiple of the dimension"));
      return in_file(path,
                     [&]()
                     {
                       return LocalProblem(
                         p->spacedim,
                         to_triplets(*p->W, "W"),
                         dealii::Vector<double>(p->q, p->q + n),
                         std::vector<double>(p->mu, p->mu + nc),
                         title_of(p->info),
                         storage);
                     });
    }


    GlobalProblem
    read_global(const std::string &path)
    {
      check_is_form(path, Form::global);
      // before libfclib allocates from the headers (see FileLayout)
      const FileLayout layout(path, Form::global);
      std::unique_ptr<fclib_global, void (*)(fclib_global *)> p(
        nullptr, fclib_delete_global);
      {
        const LibfclibCall call(path, "read");
        p.reset(fclib_read_global(path.c_str()));
      }
      AssertThrow(p && p->M && p->H && p->f && p->w && p->mu,
                  dealii::ExcMessage("libfclib could not read the global "
                                     "problem in `" +
                                     path + "'"));
      check_dimension(path, p->spacedim);
      const unsigned int n = p->M->m, m = p->H->n;
      AssertThrow(m % p->spacedim == 0,
                  dealii::ExcMessage("FCLIB file `" + path + "': H has " +
                                     std::to_string(m) +
                                     " columns, not a multiple of the "
                                     "dimension"));
      return in_file(path,
                     [&]()
                     {
                       return GlobalProblem(
                         p->spacedim,
                         to_triplets(*p->M, "M"),
                         to_triplets(*p->H, "H"),
                         dealii::Vector<double>(p->f, p->f + n),
                         dealii::Vector<double>(p->w, p->w + m),
                         std::vector<double>(p->mu, p->mu + m / p->spacedim),
                         title_of(p->info));
                     });
    }


    LocalProblem
    read_as_local(const std::string &path, const Storage storage)
    {
      if (form_of(path) == Form::local)
        return read_local(path, storage);
      return read_global(path).reduce_to_local(storage);
    }


    void
    write_local(const std::string            &path,
                const LocalProblem           &problem,
                const dealii::Vector<double> &r,
                const std::string            &description)
    {
      AssertThrow(r.size() == 0 || r.size() == problem.size(),
                  dealii::ExcMessage("FCLIB solution of wrong size"));
      TemporaryFile file(path);
      remove_existing(file.name());
      CscMatrix           W(problem.W());
      std::vector<double> q(problem.q().begin(), problem.q().end());
      std::vector<double> mu(problem.mu());
      Info info(problem.title().empty() ? "dualcontact" : problem.title(),
                description,
                "local Coulomb frictional contact, u = W r + q");
      fclib_local local{};
      local.W        = &W.matrix;
      local.mu       = mu.data();
      local.q        = q.data();
      local.spacedim = problem.spacedim();
      local.info     = &info.info;
      {
        const LibfclibCall call(path, "write", file.name());
        check_written(fclib_write_local(&local, file.name().c_str()), path);
        if (r.size() > 0)
        {
          dealii::Vector<double> u;
          problem.velocity(u, r);
          write_solution(path, file.name(), r, u);
        }
      }
      file.commit();
    }


    void
    write_global(const std::string            &path,
                 const GlobalProblem          &problem,
                 const dealii::Vector<double> &r,
                 const std::string            &description)
    {
      AssertThrow(r.size() == 0 || r.size() == problem.H().n(),
                  dealii::ExcMessage("FCLIB solution of wrong size"));
      TemporaryFile file(path);
      remove_existing(file.name());
      // M in full (both triangles): the reader mirrors only upper-only data
      CscMatrix           M(problem.M()), H(problem.H());
      std::vector<double> f(problem.f().begin(), problem.f().end());
      std::vector<double> w(problem.w().begin(), problem.w().end());
      std::vector<double> mu(problem.mu());
      Info info(problem.title().empty() ? "dualcontact" : problem.title(),
                description,
                "global Coulomb frictional contact, M v = H r + f, "
                "u = H'v + w");
      fclib_global global{};
      global.M        = &M.matrix;
      global.H        = &H.matrix;
      global.mu       = mu.data();
      global.f        = f.data();
      global.w        = w.data();
      global.spacedim = problem.spacedim();
      global.info     = &info.info;
      {
        const LibfclibCall call(path, "write", file.name());
        check_written(fclib_write_global(&global, file.name().c_str()), path);
        if (r.size() > 0)
        {
          dealii::Vector<double> v, u(r.size());
          problem.velocity(v, r);
          problem.H().Tvmult(u, v);
          u += problem.w();
          write_solution(path, file.name(), r, u, &v);
        }
      }
      file.commit();
    }


    dealii::Vector<double>
    read_solution_r(const std::string &path)
    {
      // the layout checks /solution/r against the problem's size before
      // libfclib allocates it
      const FileLayout layout(path, form_of(path));
      if (!layout.has_solution())
        return {};
      const std::size_t size = layout.contact_size();
      std::unique_ptr<fclib_solution, void (*)(fclib_solution *)> s(
        nullptr, [](fclib_solution *p) { fclib_delete_solutions(p, 1); });
      {
        const LibfclibCall call(path, "read the solution of");
        s.reset(fclib_read_solution(path.c_str()));
      }
      AssertThrow(s && s->r,
                  dealii::ExcMessage("libfclib could not read the solution "
                                     "in `" +
                                     path + "'"));
      return dealii::Vector<double>(s->r, s->r + size);
    }
  } // namespace fclib
} // namespace dualcontact
