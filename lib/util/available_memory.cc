#include <util/available_memory.h>

#include <fstream>
#include <sstream>
#include <string>

namespace dualcontact
{
  namespace util
  {
    std::uint64_t
    available_memory()
    {
      std::ifstream in("/proc/meminfo");
      std::string   line;
      while (std::getline(in, line))
        if (line.rfind("MemAvailable:", 0) == 0)
        {
          std::istringstream fields(line.substr(13));
          std::uint64_t      kilobytes = 0;
          if (fields >> kilobytes)
            return kilobytes * 1024;
        }
      return 0;
    }
  } // namespace util
} // namespace dualcontact
