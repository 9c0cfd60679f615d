// io::OutputFolder: nothing is created by the check; files appear under
// their final names only after commit(); an uncommitted folder removes its
// temporary files and the folders it created; unwritable paths are refused
// up front; a write that fails (a full disk) names the file and the cause. Also
// io::locate_file and the parameter-file helpers.

#include <deal.II/base/exceptions.h>

#include <io/file_locator.h>
#include <io/output_folder.h>
#include <io/parameter_file.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <test_tools.h>

namespace fs = std::filesystem;

using test_tools::check;
using test_tools::error_of;


int
main()
{
  using namespace dualcontact::io;
  const fs::path root = fs::absolute("output_folder_test");
  fs::remove_all(root);
  fs::create_directories(root);

  // a failed run: nothing stays, not even the folders it created
  {
    const std::string path = (root / "a" / "b").string();
    {
      OutputFolder folder(path, "(here)");
      check(!fs::exists(root / "a"), "the check creates nothing");
      folder.write("x.txt", [](std::ostream &out) { out << "x\n"; });
      check(fs::exists(fs::path(path) / ".x.txt.tmp"),
            "a file is first written under a temporary name");
      check(!fs::exists(fs::path(path) / "x.txt"),
            "... and not under its final name");
    }
    check(!fs::exists(root / "a"),
          "an uncommitted folder removes its files and created folders");
  }

  // a complete run: the final names, no temporary files
  {
    const std::string path = (root / "c").string();
    OutputFolder      folder(path, "(here)");
    folder.write("x.txt", [](std::ostream &out) { out << "x\n"; });
    folder.write("y.txt", [](std::ostream &out) { out << "y\n"; });
    folder.commit();
    check(fs::exists(fs::path(path) / "x.txt") &&
            fs::exists(fs::path(path) / "y.txt") &&
            !fs::exists(fs::path(path) / ".x.txt.tmp"),
          "commit renames every file");
  }

  // a folder below a file cannot be made
  {
    std::ofstream(root / "file") << "x";
    const std::string message = error_of(
      [&]() { OutputFolder((root / "file" / "out").string(), "(`set X')"); });
    check(message.find("is not a directory") != std::string::npos &&
            message.find("(`set X')") != std::string::npos,
          "a folder below a file is refused: " + message);
  }

  // a symbolic-link loop on the way (issue 49): the folder, the parameter
  // and the cause named, not std::filesystem's raw error
  {
    fs::create_symlink("loop", root / "loop");
    const std::string message = error_of(
      [&]()
      {
        OutputFolder folder((root / "loop" / "out").string(),
                            "(`set Output folder' in `subsection Output')");
        folder.lock();
      });
    check(message.find("Cannot write the output folder `" +
                       (root / "loop" / "out").string() +
                       "' (`set Output folder' in `subsection Output'): `") !=
              std::string::npos &&
            message.find("Too many levels of symbolic links") !=
              std::string::npos,
          "a symbolic-link loop names the folder, parameter and cause: " +
            message);
  }

  // a full disk: the message names the file and the cause (the temporary
  // name is made a link to /dev/full, where every write fails with ENOSPC)
  if (fs::exists("/dev/full"))
  {
    const fs::path path = root / "full";
    fs::create_directories(path);
    fs::create_symlink("/dev/full", path / ".big.txt.tmp");
    const std::string message = error_of(
      [&]()
      {
        OutputFolder folder(path.string(), "(here)");
        folder.write("big.txt",
                     [](std::ostream &out)
                     { out << std::string(1 << 20, 'x') << "\n"; });
      });
    check(message.find("full/big.txt'") != std::string::npos &&
            message.find("No space left on device") != std::string::npos,
          "a full disk names the file and the cause: " + message);
  }
  else
    std::cout << "skipped: no /dev/full for the full-disk check" << std::endl;

  // locate_file: relative to the parameter file's folder, else an error
  // listing the paths tried
  {
    fs::create_directories(root / "prm");
    std::ofstream(root / "prm" / "mesh.msh") << "x";
    check(locate_file("mesh.msh", (root / "prm").string(), "(here)") ==
            (root / "prm" / "mesh.msh").string(),
          "a file next to the parameter file is found");
    const std::string message = error_of(
      [&]() { locate_file("nothing.msh", (root / "prm").string(), "(here)"); });
    check(message.find("Paths tried") != std::string::npos &&
            message.find((root / "prm" / "nothing.msh").string()) !=
              std::string::npos,
          "a missing file lists the paths tried");
  }

  // the subsection a line is in, and how a parameter is named
  {
    const fs::path file = root / "test.prm";
    std::ofstream(file) << "set A = 1\n"
                           "subsection Body 1  # comment\n"
                           "  subsection Material 2\n"
                           "    set E = 1\n"
                           "  end\n"
                           "  set F = 2\n"
                           "end\n";
    check(subsection_path_at_line(file.string(), 1) == "", "top level");
    check(subsection_path_at_line(file.string(), 4) == "Body 1/Material 2",
          "nested subsection");
    check(subsection_path_at_line(file.string(), 6) == "Body 1",
          "after an end");
    check(parameter_location("Body 1/Material 2", "Young's modulus") ==
            "(`set Young's modulus' in `subsection Body 1/Material 2')",
          "ASPECT-style location");
  }

  fs::remove_all(root);
  return test_tools::finish();
}
