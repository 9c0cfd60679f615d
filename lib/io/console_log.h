#pragma once

#include <ostream>
#include <sstream>
#include <streambuf>
#include <string>

namespace dualcontact
{
  namespace io
  {
    /**
     * The console of a run, kept: an output stream that writes to a
     * terminal stream (std::cout) and also into a record, whose text the
     * run writes into its output folder as log.txt.  The program builds
     * its dealii::ConditionalOStream on stream(), so that every line the
     * console shows (rank 0) is in the record.
     *
     * With `Output/Verbosity = quiet' the terminal is switched off
     * (show_on_terminal(false)) and the record still receives every line:
     * a quiet run prints nothing but errors and still leaves its full log.
     */
    class ConsoleLog
    {
    public:
      explicit ConsoleLog(std::ostream &terminal);

      ConsoleLog(const ConsoleLog &) = delete;
      ConsoleLog &
      operator=(const ConsoleLog &) = delete;

      /** The stream to write to: the terminal (if shown) and the record. */
      std::ostream &
      stream();

      /** Whether what is written from now on also goes to the terminal. */
      void
      show_on_terminal(const bool show);

      /** Add @p text to the record only (e.g. an error printed on stderr). */
      void
      add_to_record(const std::string &text);

      /** Everything written so far. */
      std::string
      text() const;

    private:
      /** Writes every character to the record and, if shown, the terminal. */
      class TeeBuffer : public std::streambuf
      {
      public:
        TeeBuffer(std::streambuf *terminal, std::streambuf *record);
        bool show_terminal = true;

      protected:
        int_type
        overflow(int_type character) override;
        std::streamsize
        xsputn(const char *text, std::streamsize count) override;
        int
        sync() override;

      private:
        std::streambuf *terminal_;
        std::streambuf *record_;
      };

      std::ostream      &terminal_;
      std::ostringstream record_;
      TeeBuffer          buffer_;
      std::ostream       stream_;
    };
  } // namespace io
} // namespace dualcontact
