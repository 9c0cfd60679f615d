#pragma once

#include <string>

namespace dualcontact
{
  namespace io
  {
    /**
     * Find a file named in a parameter file.  A relative @p name is looked up
     * (1) as given, i.e. relative to the current working directory, (2)
     * relative to @p parameter_file_folder (the folder of the .prm file that
     * names it), (3) relative to the source tree (DUALCONTACT_SOURCE_DIR), so
     * that `set Gmsh file = meshes/plate.msh` works from anywhere.  An
     * absolute name is only tried as given.
     *
     * Returns the first path that is a readable regular file.  Throws an
     * ExcMessage naming @p parameter_location and listing every path tried.
     */
    std::string
    locate_file(const std::string &name,
                const std::string &parameter_file_folder,
                const std::string &parameter_location);

    /** The folder holding @p file_name ("." if it has none). */
    std::string
    folder_of(const std::string &file_name);
  } // namespace io
} // namespace dualcontact
