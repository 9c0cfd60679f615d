#include <io/console_log.h>

namespace dualcontact
{
  namespace io
  {
    ConsoleLog::TeeBuffer::TeeBuffer(std::streambuf *terminal,
                                     std::streambuf *record)
        : terminal_(terminal)
        , record_(record)
    {
    }


    ConsoleLog::TeeBuffer::int_type
    ConsoleLog::TeeBuffer::overflow(const int_type character)
    {
      if (traits_type::eq_int_type(character, traits_type::eof()))
        return traits_type::not_eof(character);
      const char c = traits_type::to_char_type(character);
      if (record_->sputc(c) == traits_type::eof())
        return traits_type::eof();
      if (show_terminal && terminal_->sputc(c) == traits_type::eof())
        return traits_type::eof();
      return character;
    }


    std::streamsize
    ConsoleLog::TeeBuffer::xsputn(const char *text, const std::streamsize count)
    {
      const std::streamsize written = record_->sputn(text, count);
      if (show_terminal)
        terminal_->sputn(text, count);
      return written;
    }


    int
    ConsoleLog::TeeBuffer::sync()
    {
      // std::endl flushes: the terminal shows each line at once
      return show_terminal ? terminal_->pubsync() : 0;
    }


    ConsoleLog::ConsoleLog(std::ostream &terminal)
        : terminal_(terminal)
        , buffer_(terminal.rdbuf(), record_.rdbuf())
        , stream_(&buffer_)
    {
    }


    std::ostream &
    ConsoleLog::stream()
    {
      return stream_;
    }


    void
    ConsoleLog::show_on_terminal(const bool show)
    {
      stream_.flush();
      buffer_.show_terminal = show;
    }


    void
    ConsoleLog::add_to_record(const std::string &text)
    {
      stream_.flush();
      record_ << text;
    }


    std::string
    ConsoleLog::text() const
    {
      return record_.str();
    }
  } // namespace io
} // namespace dualcontact
