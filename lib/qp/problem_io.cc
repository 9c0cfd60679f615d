#include <qp/problem_io.h>
#include <util/available_memory.h>
#include <util/file_text.h>

#include <deal.II/base/exceptions.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <numeric>
#include <sstream>

namespace dualcontact
{
  namespace qp
  {
    namespace
    {
      /**
       * Throws, through @p cursor (file and line), unless the memory a
       * matrix of @p n_rows rows and @p n_entries stored entries needs is
       * available: the arrays of the triplets, of the counting sort and of
       * the sparse matrix take some 40 bytes a row and 40 an entry, and
       * the solvers' vectors a few more a row.  A size line of 10^9 rows
       * would otherwise end in std::bad_alloc, naming nothing.
       */
      template <typename Cursor>
      void
      check_memory_for_matrix(const Cursor       &cursor,
                              const std::uint64_t n_rows,
                              const std::uint64_t n_cols,
                              const std::uint64_t n_entries)
      {
        const std::uint64_t available = util::available_memory();
        if (available == 0)
          return; // unknown
        const std::uint64_t needed = 80 * n_rows + 40 * n_entries;
        if (needed <= available)
          return;
        std::ostringstream text;
        text << std::setprecision(3) << "the size line announces a " << n_rows
             << " x " << n_cols << " matrix with " << n_entries
             << " entries, which needs about " << needed / 1e9
             << " GB to read and solve, but only " << available / 1e9
             << " GB of memory are available (MemAvailable in /proc/meminfo)";
        cursor.fail(text.str());
      }


      /**
       * Cursor over a text buffer that knows its line number, so that
       * every parse error can say where it happened.
       */
      class TextCursor
      {
      public:
        TextCursor(const std::string &text, const std::string &filename)
            : begin(text.data())
            , pos(text.data())
            , end(text.data() + text.size())
            , filename(filename)
        {
        }

        bool
        at_end() const
        {
          return pos >= end;
        }

        /// skip spaces and tabs (not newlines)
        void
        skip_blanks()
        {
          while (pos < end && (*pos == ' ' || *pos == '\t' || *pos == '\r'))
            ++pos;
        }

        /// go to the start of the next line
        void
        next_line()
        {
          while (pos < end && *pos != '\n')
            ++pos;
          if (pos < end)
          {
            ++pos;
            ++line;
          }
        }

        /// true if the rest of the current line is blank
        bool
        line_is_blank()
        {
          skip_blanks();
          return pos >= end || *pos == '\n';
        }

        char
        peek() const
        {
          return pos < end ? *pos : '\0';
        }

        template <typename Integer>
        Integer
        read_integer(const char *what)
        {
          skip_blanks();
          Integer    value{};
          const auto result = std::from_chars(pos, end, value);
          if (result.ec != std::errc())
            fail(std::string("expected an integer (") + what + ")");
          pos = result.ptr;
          return value;
        }

        double
        read_double(const char *what)
        {
          skip_blanks();
          // from_chars rejects a leading '+'; Matrix Market files have them
          if (pos < end && *pos == '+')
            ++pos;
          double     value = 0.;
          const auto result =
            std::from_chars(pos, end, value, std::chars_format::general);
          if (result.ec != std::errc())
            fail(std::string("expected a number (") + what + ")");
          pos = result.ptr;
          return value;
        }

        [[noreturn]] void
        fail(const std::string &message) const
        {
          // show the offending line, cut to a readable length
          const char *line_begin = pos;
          while (line_begin > begin && *(line_begin - 1) != '\n')
            --line_begin;
          const char *line_end = pos;
          while (line_end < end && *line_end != '\n')
            ++line_end;
          std::string text(line_begin,
                           std::min<std::size_t>(line_end - line_begin, 80));
          AssertThrow(false,
                      dealii::ExcMessage(filename + ":" + std::to_string(line) +
                                         ": " + message + " in line '" + text +
                                         "'."));
          std::abort();
        }

        const char  *begin;
        const char  *pos;
        const char  *end;
        std::string  filename;
        unsigned int line = 1;
      };


      std::string
      lower_case(std::string text)
      {
        std::transform(text.begin(),
                       text.end(),
                       text.begin(),
                       [](char c) {
                         return static_cast<char>(
                           std::tolower(static_cast<unsigned char>(c)));
                       });
        return text;
      }


      /**
       * Build @p pattern and @p matrix from coordinate triplets (0-based,
       * any order, duplicates summed).  Counting sort by row, then a sort of
       * each (short) row by column: O(nnz) plus small sorts.
       */
      void
      build_from_triplets(const unsigned int               n_rows,
                          const unsigned int               n_cols,
                          const std::vector<unsigned int> &rows,
                          const std::vector<unsigned int> &cols,
                          const std::vector<double>       &values,
                          dealii::SparsityPattern         &pattern,
                          dealii::SparseMatrix<double>    &matrix)
      {
        const std::size_t        nnz = rows.size();
        std::vector<std::size_t> row_start(n_rows + 1, 0);
        for (std::size_t k = 0; k < nnz; ++k)
          ++row_start[rows[k] + 1];
        std::partial_sum(row_start.begin(), row_start.end(), row_start.begin());
        std::vector<std::pair<unsigned int, double>> entries(nnz);
        {
          std::vector<std::size_t> fill(row_start.begin(), row_start.end() - 1);
          for (std::size_t k = 0; k < nnz; ++k)
            entries[fill[rows[k]]++] = {cols[k], values[k]};
        }

        // sort each row and sum duplicates in place; the de-duplicated
        // entries of row r are entries[row_start[r] .. + n_distinct[r])
        std::vector<unsigned int> n_distinct(n_rows, 0);
        std::vector<unsigned int> pattern_length(n_rows, 0);
        const auto                by_column = [](const auto &a, const auto &b)
        { return a.first < b.first; };
        for (unsigned int r = 0; r < n_rows; ++r)
        {
          auto *first = entries.data() + row_start[r];
          auto *last  = entries.data() + row_start[r + 1];
          std::sort(first, last, by_column);
          auto *out = first;
          for (auto *e = first; e < last; ++e)
          {
            if (out != first && (out - 1)->first == e->first)
              (out - 1)->second += e->second;
            else
              *out++ = *e;
          }
          n_distinct[r]     = static_cast<unsigned int>(out - first);
          pattern_length[r] = n_distinct[r];
          // a square pattern stores the diagonal even if not given
          if (n_rows == n_cols &&
              !std::binary_search(first, out, std::make_pair(r, 0.), by_column))
            ++pattern_length[r];
        }

        pattern.reinit(n_rows, n_cols, pattern_length);
        std::vector<unsigned int> column_buffer;
        for (unsigned int r = 0; r < n_rows; ++r)
        {
          const auto *first = entries.data() + row_start[r];
          column_buffer.resize(n_distinct[r]);
          for (unsigned int k = 0; k < n_distinct[r]; ++k)
            column_buffer[k] = first[k].first;
          pattern.add_entries(r,
                              column_buffer.begin(),
                              column_buffer.end(),
                              true);
        }
        pattern.compress();
        matrix.reinit(pattern);

        std::vector<dealii::types::global_dof_index> col_index;
        std::vector<double>                          row_values;
        for (unsigned int r = 0; r < n_rows; ++r)
        {
          const auto *first = entries.data() + row_start[r];
          col_index.resize(n_distinct[r]);
          row_values.resize(n_distinct[r]);
          for (unsigned int k = 0; k < n_distinct[r]; ++k)
          {
            col_index[k]  = first[k].first;
            row_values[k] = first[k].second;
          }
          matrix.set(
            r, col_index.size(), col_index.data(), row_values.data(), false);
        }
      }

      /**
       * The first entry (r, c) of @p matrix (square) whose mirror (c, r)
       * differs by more than 1e-10 times the largest magnitude, as a message
       * ("" if symmetric).  The QP solvers assume a symmetric Hessian: a
       * `general' file holding only one triangle would be solved as a
       * different problem and reported converged.
       */
      std::string
      asymmetry(const dealii::SparseMatrix<double> &matrix)
      {
        double largest = 0;
        for (const auto &entry : matrix)
          largest = std::max(largest, std::abs(entry.value()));
        const double tolerance = 1e-10 * largest;
        for (const auto &entry : matrix)
        {
          const auto   r      = entry.row();
          const auto   c      = entry.column();
          const double mirror = matrix.el(c, r);
          if (std::abs(entry.value() - mirror) > tolerance)
          {
            std::ostringstream text;
            text << std::setprecision(17) << "A(" << r + 1 << ", " << c + 1
                 << ") = " << entry.value() << " but A(" << c + 1 << ", "
                 << r + 1 << ") = " << mirror;
            return text.str();
          }
        }
        return "";
      }
    } // namespace


    unsigned int
    ProblemData::ConstraintBlock::block_size() const
    {
      if (type == "disc" || type == "ellipse")
        return 2;
      if (type == "cone")
        return 3;
      return 1;
    }


    std::size_t
    ProblemData::ConstraintBlock::n_unknowns() const
    {
      return std::size_t(count) * block_size();
    }


    unsigned int
    ProblemData::size() const
    {
      return rhs.size();
    }


    bool
    ProblemData::has_equality() const
    {
      return !equality_matrix.empty();
    }


    void
    read_matrix_market(const std::string            &filename,
                       dealii::SparsityPattern      &pattern,
                       dealii::SparseMatrix<double> &matrix)
    {
      const std::string text = util::read_file_text(filename, "Matrix Market");
      TextCursor        cursor(text, filename);

      // header: %%MatrixMarket matrix coordinate real general|symmetric
      std::string header;
      while (!cursor.at_end() && cursor.peek() != '\n')
        header.push_back(*cursor.pos++);
      std::istringstream header_stream(lower_case(header));
      std::string        banner, object, format, field, symmetry;
      header_stream >> banner >> object >> format >> field >> symmetry;
      if (banner != "%%matrixmarket")
        cursor.fail("missing '%%MatrixMarket' header");
      if (object != "matrix" || format != "coordinate")
        cursor.fail("only 'matrix coordinate' files are supported (got '" +
                    object + " " + format + "')");
      if (field != "real" && field != "integer" && field != "double")
        cursor.fail("only real or integer matrices are supported (got '" +
                    field + "')");
      if (symmetry != "general" && symmetry != "symmetric")
        cursor.fail("only general or symmetric matrices are supported (got '" +
                    symmetry + "')");
      const bool symmetric = (symmetry == "symmetric");
      cursor.next_line();

      // comments, then the size line
      while (!cursor.at_end() &&
             (cursor.peek() == '%' || cursor.line_is_blank()))
        cursor.next_line();
      if (cursor.at_end())
        cursor.fail("missing size line 'rows columns entries'");
      const auto n_rows    = cursor.read_integer<long>("number of rows");
      const auto n_cols    = cursor.read_integer<long>("number of columns");
      const auto n_entries = cursor.read_integer<long>("number of entries");
      if (n_rows <= 0 || n_cols <= 0 || n_entries < 0 ||
          n_rows > std::numeric_limits<int>::max() ||
          n_cols > std::numeric_limits<int>::max())
        cursor.fail("invalid matrix size");
      if (symmetric && n_rows != n_cols)
        cursor.fail("a symmetric matrix must be square");
      // (the entries at most as many as the rest of the file can hold:
      // an entry count beyond that is the error checked below)
      check_memory_for_matrix(
        cursor,
        n_rows,
        n_cols,
        std::min<std::uint64_t>(n_entries, (cursor.end - cursor.pos) / 6 + 1) *
          (symmetric ? 2 : 1));
      cursor.next_line();
      // an entry line takes at least 6 bytes ("1 1 1\n"): check the
      // announced count against the file before reserving memory for it
      const auto bytes_left = static_cast<std::size_t>(cursor.end - cursor.pos);
      if (static_cast<std::size_t>(n_entries) > bytes_left / 6 + 1)
        cursor.fail("the size line announces " + std::to_string(n_entries) +
                    " entries, but the remaining " +
                    std::to_string(bytes_left) +
                    " bytes of the file hold at most " +
                    std::to_string(bytes_left / 6 + 1) +
                    " (truncated file or wrong size line)");

      const std::size_t reserve =
        static_cast<std::size_t>(n_entries) * (symmetric ? 2 : 1);
      std::vector<unsigned int> rows, cols;
      std::vector<double>       values;
      rows.reserve(reserve);
      cols.reserve(reserve);
      values.reserve(reserve);

      long n_read = 0;
      while (n_read < n_entries)
      {
        if (cursor.at_end())
          cursor.fail("file ends after " + std::to_string(n_read) + " of " +
                      std::to_string(n_entries) + " entries");
        if (cursor.peek() == '%' || cursor.line_is_blank())
        {
          cursor.next_line();
          continue;
        }
        const long i = cursor.read_integer<long>("row index");
        const long j = cursor.read_integer<long>("column index");
        if (i < 1 || i > n_rows || j < 1 || j > n_cols)
          cursor.fail("index (" + std::to_string(i) + ", " + std::to_string(j) +
                      ") outside the " + std::to_string(n_rows) + " x " +
                      std::to_string(n_cols) + " matrix");
        const double value = cursor.read_double("value");
        if (!std::isfinite(value))
          cursor.fail("non-finite value");
        if (!cursor.line_is_blank())
          cursor.fail("unexpected text after 'row column value'");
        rows.push_back(static_cast<unsigned int>(i - 1));
        cols.push_back(static_cast<unsigned int>(j - 1));
        values.push_back(value);
        if (symmetric && i != j)
        {
          rows.push_back(static_cast<unsigned int>(j - 1));
          cols.push_back(static_cast<unsigned int>(i - 1));
          values.push_back(value);
        }
        ++n_read;
        cursor.next_line();
      }
      while (!cursor.at_end())
      {
        if (cursor.peek() != '%' && !cursor.line_is_blank())
          cursor.fail("more entries than the " + std::to_string(n_entries) +
                      " announced in the size line");
        cursor.next_line();
      }

      build_from_triplets(static_cast<unsigned int>(n_rows),
                          static_cast<unsigned int>(n_cols),
                          rows,
                          cols,
                          values,
                          pattern,
                          matrix);
    }


    void
    write_matrix_market(const std::string                  &filename,
                        const dealii::SparseMatrix<double> &matrix,
                        const bool                          symmetric)
    {
      std::FILE *file = std::fopen(filename.c_str(), "wb");
      AssertThrow(file != nullptr,
                  dealii::ExcMessage("Cannot write '" + filename + "'."));
      std::size_t n_entries = 0;
      for (unsigned int r = 0; r < matrix.m(); ++r)
        for (auto it = matrix.begin(r); it != matrix.end(r); ++it)
          if (!symmetric || it->column() <= r)
            ++n_entries;
      std::fprintf(file,
                   "%%%%MatrixMarket matrix coordinate real %s\n%u %u %zu\n",
                   symmetric ? "symmetric" : "general",
                   static_cast<unsigned int>(matrix.m()),
                   static_cast<unsigned int>(matrix.n()),
                   n_entries);
      std::vector<char> buffer(1 << 20);
      std::size_t       used = 0;
      for (unsigned int r = 0; r < matrix.m(); ++r)
      {
        // write row-sorted entries: deal.II keeps the diagonal first
        std::vector<std::pair<unsigned int, double>> row;
        for (auto it = matrix.begin(r); it != matrix.end(r); ++it)
          if (!symmetric || it->column() <= r)
            row.emplace_back(it->column(), it->value());
        std::sort(row.begin(), row.end());
        for (const auto &[column, value] : row)
        {
          if (used + 64 > buffer.size())
          {
            std::fwrite(buffer.data(), 1, used, file);
            used = 0;
          }
          char *p   = buffer.data() + used;
          char *end = buffer.data() + buffer.size();
          p         = std::to_chars(p, end, r + 1).ptr;
          *p++      = ' ';
          p         = std::to_chars(p, end, column + 1).ptr;
          *p++      = ' ';
          p         = std::to_chars(p, end, value).ptr;
          *p++      = '\n';
          used      = p - buffer.data();
        }
      }
      std::fwrite(buffer.data(), 1, used, file);
      const bool ok = (std::fclose(file) == 0);
      AssertThrow(ok, dealii::ExcMessage("Error writing '" + filename + "'."));
    }


    std::vector<double>
    read_vector_file(const std::string &filename,
                     const long         expected_size,
                     const std::string &what)
    {
      const std::string   text = util::read_file_text(filename, what);
      TextCursor          cursor(text, filename);
      std::vector<double> values;
      if (expected_size >= 0)
        values.reserve(expected_size);
      while (!cursor.at_end())
      {
        if (cursor.peek() == '%' || cursor.peek() == '#' ||
            cursor.line_is_blank())
        {
          cursor.next_line();
          continue;
        }
        const double value = cursor.read_double("one number per line");
        if (std::isnan(value))
          cursor.fail("NaN value");
        if (!cursor.line_is_blank())
          cursor.fail("expected one number per line");
        values.push_back(value);
        cursor.next_line();
      }
      AssertThrow(expected_size < 0 ||
                    static_cast<long>(values.size()) == expected_size,
                  dealii::ExcMessage(filename + ": " +
                                     (what.empty() ? "vector" : what) +
                                     " has " + std::to_string(values.size()) +
                                     " values, expected " +
                                     std::to_string(expected_size) + "."));
      return values;
    }


    void
    write_vector_file(const std::string         &filename,
                      const std::vector<double> &values)
    {
      std::FILE *file = std::fopen(filename.c_str(), "wb");
      AssertThrow(file != nullptr,
                  dealii::ExcMessage("Cannot write '" + filename + "'."));
      std::vector<char> buffer(1 << 20);
      std::size_t       used = 0;
      for (const double value : values)
      {
        if (used + 40 > buffer.size())
        {
          std::fwrite(buffer.data(), 1, used, file);
          used = 0;
        }
        char *p = buffer.data() + used;
        p       = std::to_chars(p, buffer.data() + buffer.size(), value).ptr;
        *p++    = '\n';
        used    = p - buffer.data();
      }
      std::fwrite(buffer.data(), 1, used, file);
      const bool ok = (std::fclose(file) == 0);
      AssertThrow(ok, dealii::ExcMessage("Error writing '" + filename + "'."));
    }


    void
    write_vector_file(const std::string            &filename,
                      const dealii::Vector<double> &values)
    {
      write_vector_file(filename,
                        std::vector<double>(values.begin(), values.end()));
    }


    namespace
    {
      /// Everything read_problem() needs to say where an error is.
      struct JsonContext
      {
        std::string           json_file;
        std::filesystem::path directory;

        [[noreturn]] void
        fail(const std::string &field, const std::string &message) const
        {
          AssertThrow(false,
                      dealii::ExcMessage(json_file + ": field '" + field +
                                         "': " + message));
          std::abort();
        }

        std::string
        resolve(const std::string &name) const
        {
          const std::filesystem::path path(name);
          return path.is_absolute() ? path.string() :
                                      (directory / path).string();
        }

        std::string
        file_name(const nlohmann::json &value, const std::string &field) const
        {
          if (!value.is_string())
            fail(field, "expected a file name (string)");
          const std::string name = value.get<std::string>();
          if (name.empty())
            fail(field, "empty file name");
          const std::string path = resolve(name);
          if (!std::filesystem::exists(path))
            fail(field, "file '" + path + "' does not exist");
          return path;
        }

        /// A value that is a number (same for every entry) or a file.
        std::vector<double>
        values(const nlohmann::json &value,
               const std::string    &field,
               const std::size_t     size) const
        {
          if (value.is_number())
            return std::vector<double>(size, value.get<double>());
          if (value.is_string())
            return read_vector_file(file_name(value, field), size, field);
          fail(field, "expected a number or a file name");
        }

        unsigned int
        count(const nlohmann::json &object,
              const std::string    &key,
              const std::string    &field) const
        {
          if (!object.contains(key))
            fail(field + "." + key, "missing");
          const auto &value = object.at(key);
          if (!value.is_number_integer() || value.get<long>() < 0 ||
              value.get<long>() > std::numeric_limits<int>::max())
            fail(field + "." + key, "expected a non-negative integer");
          return value.get<unsigned int>();
        }

        void
        check_keys(const nlohmann::json           &object,
                   const std::vector<std::string> &allowed,
                   const std::string              &field) const
        {
          for (const auto &item : object.items())
            if (std::find(allowed.begin(), allowed.end(), item.key()) ==
                allowed.end())
            {
              std::string list;
              for (const auto &a : allowed)
                list += (list.empty() ? "" : ", ") + a;
              fail(field.empty() ? item.key() : field + "." + item.key(),
                   "unknown key (allowed: " + list + ")");
            }
        }
      };


      dealii::Vector<double>
      to_vector(const std::vector<double> &values)
      {
        dealii::Vector<double> v(values.size());
        std::copy(values.begin(), values.end(), v.begin());
        return v;
      }
    } // namespace


    std::string
    plain_message(const std::exception &exception)
    {
      const std::string text   = exception.what();
      const std::string marker = "Additional information:";
      const auto        begin  = text.find(marker);
      if (begin == std::string::npos)
        return text;
      auto end = text.find("Stacktrace:", begin);
      if (end == std::string::npos)
        end = text.size();
      // deal.II wraps the message at 80 columns with indentation: join
      std::string        message;
      std::istringstream lines(
        text.substr(begin + marker.size(), end - begin - marker.size()));
      std::string line;
      while (std::getline(lines, line))
      {
        const auto first = line.find_first_not_of(" \t");
        if (first == std::string::npos)
          continue;
        const auto last = line.find_last_not_of(" \t");
        if (!message.empty())
          message += ' ';
        message += line.substr(first, last - first + 1);
      }
      return message;
    }


    std::unique_ptr<ProblemData>
    read_problem(const std::string &json_filename)
    {
      JsonContext context;
      context.json_file = json_filename;
      context.directory = std::filesystem::path(json_filename).parent_path();

      std::ifstream in(json_filename);
      AssertThrow(in,
                  dealii::ExcMessage("Cannot open problem file '" +
                                     json_filename + "'."));
      nlohmann::json root;
      try
      {
        in >> root;
      }
      catch (const nlohmann::json::exception &e)
      {
        AssertThrow(false,
                    dealii::ExcMessage(json_filename +
                                       ": not valid JSON: " + e.what()));
      }
      AssertThrow(root.is_object(),
                  dealii::ExcMessage(json_filename +
                                     ": the top level must be a JSON object."));
      context.check_keys(root,
                         {"hessian", "rhs", "x0", "constraints", "equality"},
                         "");

      auto problem    = std::make_unique<ProblemData>();
      problem->source = json_filename;

      if (!root.contains("hessian"))
        context.fail("hessian", "missing (Matrix Market file of A)");
      {
        const std::string file = context.file_name(root["hessian"], "hessian");
        read_matrix_market(file, problem->hessian_pattern, problem->hessian);
        if (problem->hessian.m() != problem->hessian.n())
          context.fail("hessian",
                       "'" + file + "' is " +
                         std::to_string(problem->hessian.m()) + " x " +
                         std::to_string(problem->hessian.n()) +
                         ", the Hessian must be square");
        const std::string asymmetric = asymmetry(problem->hessian);
        if (!asymmetric.empty())
          context.fail("hessian",
                       "'" + file + "' is not symmetric: " + asymmetric +
                         " (a file holding one triangle must say "
                         "'symmetric' in its header, not 'general')");
      }
      const std::size_t n = problem->hessian.m();

      if (!root.contains("rhs"))
        context.fail("rhs", "missing (vector file of b)");
      problem->rhs = to_vector(context.values(root["rhs"], "rhs", n));

      if (root.contains("x0"))
        problem->x0 = to_vector(context.values(root["x0"], "x0", n));

      // constraint blocks
      std::vector<int> owner(n, -1);
      if (root.contains("constraints"))
      {
        const auto &list = root["constraints"];
        if (!list.is_array())
          context.fail("constraints", "expected an array of blocks");
        for (std::size_t c = 0; c < list.size(); ++c)
        {
          const std::string field = "constraints[" + std::to_string(c) + "]";
          const auto       &entry = list[c];
          if (!entry.is_object())
            context.fail(field, "expected an object");
          if (!entry.contains("type") || !entry["type"].is_string())
            context.fail(field + ".type",
                         "missing (bound, box, disc, ellipse or cone)");
          ProblemData::ConstraintBlock block;
          block.type                    = entry["type"].get<std::string>();
          std::vector<std::string> keys = {"type", "first", "count"};
          if (block.type == "bound")
            keys.push_back("lower");
          else if (block.type == "box")
            keys.insert(keys.end(), {"lower", "upper"});
          else if (block.type == "disc")
            keys.push_back("radius");
          else if (block.type == "ellipse")
            keys.insert(keys.end(), {"axes", "rotation"});
          else if (block.type == "cone")
            keys.push_back("mu");
          else
            context.fail(field + ".type",
                         "unknown type '" + block.type +
                           "' (bound, box, disc, ellipse or cone)");
          context.check_keys(entry, keys, field);
          block.first = context.count(entry, "first", field);
          block.count = context.count(entry, "count", field);
          const std::size_t last =
            std::size_t(block.first) + block.n_unknowns();
          if (last > n)
            context.fail(field,
                         "unknowns " + std::to_string(block.first) + ".." +
                           std::to_string(last) +
                           " (exclusive) exceed the problem size " +
                           std::to_string(n));
          for (std::size_t i = block.first; i < last; ++i)
          {
            if (owner[i] >= 0)
              context.fail(field,
                           "unknown " + std::to_string(i) +
                             " is already constrained by constraints[" +
                             std::to_string(owner[i]) + "]");
            owner[i] = static_cast<int>(c);
          }

          auto required = [&](const std::string &key) -> const auto &
          {
            if (!entry.contains(key))
              context.fail(field + "." + key, "missing");
            return entry[key];
          };
          if (block.type == "bound" || block.type == "box")
          {
            block.lower =
              context.values(required("lower"), field + ".lower", block.count);
            if (block.type == "box")
            {
              block.upper = context.values(required("upper"),
                                           field + ".upper",
                                           block.count);
              for (unsigned int i = 0; i < block.count; ++i)
                if (!(block.lower[i] <= block.upper[i]))
                  context.fail(field,
                               "lower > upper at entry " + std::to_string(i) +
                                 " (" + std::to_string(block.lower[i]) + " > " +
                                 std::to_string(block.upper[i]) + ")");
            }
          }
          else if (block.type == "disc")
          {
            block.radius = context.values(required("radius"),
                                          field + ".radius",
                                          block.count);
            for (unsigned int k = 0; k < block.count; ++k)
              if (!(block.radius[k] >= 0.) || !std::isfinite(block.radius[k]))
                context.fail(field + ".radius",
                             "block " + std::to_string(k) +
                               ": radius must be finite and >= 0");
          }
          else if (block.type == "ellipse")
          {
            const auto &axes = required("axes");
            if (axes.is_number())
              block.axes.assign(2 * block.count, axes.get<double>());
            else
              block.axes =
                context.values(axes, field + ".axes", 2 * block.count);
            for (unsigned int k = 0; k < 2 * block.count; ++k)
              if (!(block.axes[k] > 0.) || !std::isfinite(block.axes[k]))
                context.fail(field + ".axes",
                             "block " + std::to_string(k / 2) +
                               ": semi-axes must be finite and > 0");
            if (entry.contains("rotation"))
              block.rotation = context.values(entry["rotation"],
                                              field + ".rotation",
                                              block.count);
          }
          else if (block.type == "cone")
          {
            block.mu =
              context.values(required("mu"), field + ".mu", block.count);
            for (unsigned int k = 0; k < block.count; ++k)
              if (!(block.mu[k] >= 0.) || !std::isfinite(block.mu[k]))
                context.fail(field + ".mu",
                             "block " + std::to_string(k) +
                               ": mu must be finite and >= 0");
          }
          problem->constraints.push_back(std::move(block));
        }
      }

      if (root.contains("equality"))
      {
        const auto &equality = root["equality"];
        if (!equality.is_object())
          context.fail("equality", "expected {\"matrix\": ..., \"rhs\": ...}");
        context.check_keys(equality, {"matrix", "rhs"}, "equality");
        if (!equality.contains("matrix"))
          context.fail("equality.matrix", "missing (Matrix Market file of B)");
        const std::string file =
          context.file_name(equality["matrix"], "equality.matrix");
        read_matrix_market(file,
                           problem->equality_pattern,
                           problem->equality_matrix);
        if (problem->equality_matrix.n() != n)
          context.fail("equality.matrix",
                       "'" + file + "' has " +
                         std::to_string(problem->equality_matrix.n()) +
                         " columns, the problem has " + std::to_string(n) +
                         " unknowns");
        const std::size_t m = problem->equality_matrix.m();
        if (equality.contains("rhs"))
          problem->equality_rhs =
            to_vector(context.values(equality["rhs"], "equality.rhs", m));
        else
          problem->equality_rhs.reinit(m);
      }
      return problem;
    }


    std::string
    write_problem(const ProblemData &problem,
                  const std::string &directory,
                  const std::string &name)
    {
      std::filesystem::create_directories(directory);
      const std::filesystem::path dir(directory);
      nlohmann::json              root;

      write_matrix_market((dir / (name + "_A.mtx")).string(),
                          problem.hessian,
                          true);
      root["hessian"] = name + "_A.mtx";
      write_vector_file((dir / (name + "_b.txt")).string(), problem.rhs);
      root["rhs"] = name + "_b.txt";
      if (problem.x0.size() > 0)
      {
        write_vector_file((dir / (name + "_x0.txt")).string(), problem.x0);
        root["x0"] = name + "_x0.txt";
      }

      nlohmann::json list = nlohmann::json::array();
      for (std::size_t c = 0; c < problem.constraints.size(); ++c)
      {
        const auto    &block = problem.constraints[c];
        nlohmann::json entry;
        entry["type"]  = block.type;
        entry["first"] = block.first;
        entry["count"] = block.count;
        auto store =
          [&](const std::string &key, const std::vector<double> &values)
        {
          if (values.empty())
            return;
          // one number if all equal, else a file
          if (std::all_of(values.begin(),
                          values.end(),
                          [&](double v) { return v == values[0]; }))
            entry[key] = values[0];
          else
          {
            const std::string file =
              name + "_c" + std::to_string(c) + "_" + key + ".txt";
            write_vector_file((dir / file).string(), values);
            entry[key] = file;
          }
        };
        store("lower", block.lower);
        store("upper", block.upper);
        store("radius", block.radius);
        store("axes", block.axes);
        store("rotation", block.rotation);
        store("mu", block.mu);
        list.push_back(entry);
      }
      if (!list.empty())
        root["constraints"] = list;

      if (problem.has_equality())
      {
        write_matrix_market((dir / (name + "_B.mtx")).string(),
                            problem.equality_matrix,
                            false);
        write_vector_file((dir / (name + "_c.txt")).string(),
                          problem.equality_rhs);
        root["equality"] = {{"matrix", name + "_B.mtx"},
                            {"rhs", name + "_c.txt"}};
      }

      const std::string json_file = (dir / (name + ".json")).string();
      const std::string temporary = json_file + ".tmp";
      {
        std::ofstream out(temporary);
        AssertThrow(out,
                    dealii::ExcMessage("Cannot write '" + temporary + "'."));
        out << root.dump(2) << '\n';
      }
      std::filesystem::rename(temporary, json_file);
      return json_file;
    }
  } // namespace qp
} // namespace dualcontact
