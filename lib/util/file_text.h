#pragma once

#include <string>

namespace dualcontact
{
  namespace util
  {
    /**
     * The whole content of the file @p filename, read at once (the readers
     * then parse the text without streams).  @p what names the kind of file
     * in messages ("Matrix Market": "Cannot read Matrix Market file
     * 'x.mtx': ...").  Refuses, naming the file, a directory or other
     * non-regular file (fopen() opens a directory, whose size from
     * fseek/ftell is anything), a file that cannot be opened or read (with
     * the system's reason), and a file larger than the memory available
     * (util::available_memory()), before allocating.
     */
    std::string
    read_file_text(const std::string &filename, const std::string &what);
  } // namespace util
} // namespace dualcontact
