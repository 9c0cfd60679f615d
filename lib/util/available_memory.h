#pragma once

#include <cstdint>

namespace dualcontact
{
  namespace util
  {
    /**
     * The memory a new allocation can get on this machine without swapping
     * [bytes]: `MemAvailable' of /proc/meminfo; 0 where that cannot be read
     * (then nothing is known, and readers check nothing against it).
     * Readers of files compare the memory a header asks for with it before
     * allocating, so that a header of 10^9 rows is refused naming the file
     * instead of ending in std::bad_alloc.
     */
    std::uint64_t
    available_memory();
  } // namespace util
} // namespace dualcontact
