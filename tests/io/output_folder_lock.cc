// io::OutputFolder, issue 15: lock() refuses a second run into the same
// folder at once, naming the folder and the process; a failed locked run
// leaves nothing; a commit removes the previous run's files that it does not
// write again (and only those); write errors name the file and the cause;
// SIGTERM removes the temporary files, the lock and the created folders and
// exits with 128 + 15.

#include <deal.II/base/exceptions.h>

#include <io/output_folder.h>

#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <test_tools.h>

namespace fs = std::filesystem;

using test_tools::check;
using test_tools::contains;
using test_tools::error_of;

namespace
{
  void
  write_text(dualcontact::io::OutputFolder &folder, const std::string &name)
  {
    folder.write(name, [&](std::ostream &out) { out << name << "\n"; });
  }
} // namespace


int
main()
{
  using dualcontact::io::OutputFolder;
  const fs::path root = fs::absolute("output_folder_lock_test");
  fs::remove_all(root);
  fs::create_directories(root);
  const std::string path = (root / "out").string();

  // the first run holds the folder; the second is refused at once
  {
    OutputFolder first(path, "(here)");
    first.lock();
    check(fs::is_regular_file(fs::path(path) / ".dualcontact.lock"),
          "lock() creates the folder and the lock file");
    OutputFolder      second(path, "(here)");
    const std::string message = error_of([&] { second.lock(); });
    check(contains(message,
                   "The output folder `" + path +
                     "' is in use by another dualcontact run (process " +
                     std::to_string(getpid()) + ","),
          "a second run is refused naming the folder and the process");
  }
  check(!fs::exists(path), "a failed locked run leaves nothing behind");

  // stale files of the previous run are removed, a user's file stays
  {
    OutputFolder run(path, "(here)");
    run.lock();
    write_text(run, "results.txt");
    write_text(run, "contact_1.vtu");
    write_text(run, "contact_2.vtu");
    run.commit();
  }
  std::ofstream(fs::path(path) / "my_notes.txt") << "mine\n";
  {
    OutputFolder run(path, "(here)");
    run.lock();
    write_text(run, "results.txt");
    write_text(run, "contact_1.vtu");
    run.commit();
  }
  check(fs::exists(fs::path(path) / "results.txt") &&
          fs::exists(fs::path(path) / "contact_1.vtu") &&
          !fs::exists(fs::path(path) / "contact_2.vtu"),
        "the previous scene's contact_2.vtu is removed");
  check(fs::exists(fs::path(path) / "my_notes.txt"),
        "a file no run wrote stays");
  check(!fs::exists(fs::path(path) / ".dualcontact.lock"),
        "the lock file goes with the run");

  // a write error names the file and the cause
  {
    OutputFolder run(path, "(here)");
    run.lock();
    fs::create_directory(fs::path(path) / ".blocked.vtu.tmp");
    const std::string message =
      error_of([&] { write_text(run, "blocked.vtu"); });
    check(contains(message, ".blocked.vtu.tmp': Is a directory"),
          "a write error names the file and the cause");
    fs::remove(fs::path(path) / ".blocked.vtu.tmp");
  }

  // SIGTERM in the middle of writing: temporaries, lock and created
  // folders are removed, exit code 128 + 15
  {
    const std::string fresh = (root / "a" / "b").string();
    const pid_t       child = fork();
    if (child == 0)
    {
      OutputFolder::install_signal_handlers();
      OutputFolder run(fresh, "(here)");
      run.lock();
      write_text(run, "results.txt");
      raise(SIGTERM);
      _exit(0); // not reached
    }
    int status = 0;
    waitpid(child, &status, 0);
    check(WIFEXITED(status) && WEXITSTATUS(status) == 128 + SIGTERM,
          "SIGTERM: exit code 143");
    check(!fs::exists(root / "a"),
          "SIGTERM: the temporary file, the lock and the folders are gone");
  }

  fs::remove_all(root);
  return test_tools::finish();
}
