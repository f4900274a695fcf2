// The lock file beside an HDF5 output (io/lock_file.hpp, io/output_lock.hpp): one lock per file
// whatever name reaches it, never opened through a planted link or onto another file, made with
// the umask's mode so that a group folder's members share it, a stale one of another user named
// with the command that removes it, and a read-only folder said as such.
#include <fcntl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#ifdef AIEF_HAVE_HDF5
#include "io/hdf5_file.hpp"
#include "io/output_lock.hpp"
#include "io/temporary_files.hpp"
#endif
#include "tests/lock_run.hpp"
#include "tests/test_support.hpp"

#ifdef AIEF_HAVE_HDF5

namespace {

namespace fs = std::filesystem;
using aief::test::TempFolder;
using namespace aief::test::lock;  // start, run, wait_for, text_of, image_folder, How

// Waits until the run `pid` says in `log`.err that it waits for a lock; false when it ended first.
bool says_it_waits(pid_t pid, const fs::path& log) {
  while (text_of(log.string() + ".err").find("waiting for") == std::string::npos) {
    int status = 0;
    if (waitpid(pid, &status, WNOHANG) == pid) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return true;
}

TEST(LockFile, TwoSpellingsOfOneFileShareOneLock) {
  // Before: `ln -s real.h5 link.h5`, a batch into each at once, locking off: both exit 0, and the
  // file said "damaged or cut short (libhdf5: message not aligned)" on every rerun.
  const TempFolder temp("aief_lock_file");
  const fs::path images = image_folder(temp.path(), "i", 3), real = temp.path() / "real.h5";
  ASSERT_EQ(run(batch_into(images, real), temp.path() / "a.log"), 0);
  fs::create_symlink("real.h5", temp.path() / "link.h5");
  fs::create_directories(temp.path() / "sub");
  const std::vector<fs::path> spellings = {temp.path() / "link.h5",
                                           temp.path() / "sub" / ".." / "real.h5"};
  for (const fs::path& other : spellings) {
    const fs::path log = temp.path() / "b.log";
    pid_t writer = -1;
    {
      const aief::io::OutputLock held(real.string());
      // In this process: the second spelling is the same file, open for writing already.
      EXPECT_THROW(aief::io::OutputLock{other.string()}, aief::Error) << other;
      writer = start(batch_into(images, other), log);
      ASSERT_TRUE(says_it_waits(writer, log))
          << other << " did not wait: " << text_of(log.string() + ".err");
    }
    EXPECT_EQ(wait_for(writer), 0) << text_of(log.string() + ".err");
  }
  EXPECT_TRUE(fs::is_symlink(temp.path() / "link.h5"));
  EXPECT_EQ(
      aief::io::Hdf5File(real.string(), aief::io::Hdf5File::Mode::read).feature_names().size(), 3u);
}

TEST(LockFile, ANewFileWrittenThroughALinkIsCreatedAtItsTargetAndTheLinkKept) {
  const TempFolder temp("aief_lock_file");
  fs::create_symlink("target.h5", temp.path() / "link.h5");
  const fs::path log = temp.path() / "a.log";
  ASSERT_EQ(run(batch_into(image_folder(temp.path(), "i", 2), temp.path() / "link.h5"), log), 0)
      << text_of(log.string() + ".err");
  EXPECT_TRUE(fs::is_symlink(temp.path() / "link.h5"));
  EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(temp.path() / "target.h5")));
}

TEST(LockFile, APlantedLinkOrFileAtTheLockPathIsRefusedAndLeftUntouched) {
  // Before: `ln -s victim.txt .52d616f9aaaf608c.lock` (a predictable hash of out.h5), then a
  // batch into out.h5: exit 0 and victim.txt read "process 31572 on host vm".
  const TempFolder temp("aief_lock_file");
  const fs::path images = image_folder(temp.path(), "i", 2), output = temp.path() / "out.h5";
  const fs::path lock = aief::io::lock_path_of(output.string()),
                 victim = temp.path() / "victim.txt";
  const std::string kept = "the victim's own words\n";
  const std::vector<std::pair<std::string, void (*)(const fs::path&, const fs::path&)>> plants = {
      {"a symbolic link", [](const fs::path& v, const fs::path& l) { fs::create_symlink(v, l); }},
      {"a hard link", [](const fs::path& v, const fs::path& l) { fs::create_hard_link(v, l); }},
      {"another file", [](const fs::path&, const fs::path& l) { std::ofstream(l) << "data\n"; }},
      {"a folder", [](const fs::path&, const fs::path& l) { fs::create_directory(l); }},
  };
  for (const auto& [what, plant] : plants) {
    std::ofstream(victim) << kept;
    plant(victim, lock);
    const fs::path log = temp.path() / "a.log";
    EXPECT_EQ(run(batch_into(images, output), log), 1) << what;
    const std::string said = text_of(log.string() + ".err");
    EXPECT_NE(said.find("is taken by something that is not aief's lock file"), std::string::npos)
        << what << ": " << said;
    EXPECT_NE(said.find("rm '" + lock.string() + "'"), std::string::npos) << said;
    EXPECT_EQ(text_of(victim), kept) << what;
    EXPECT_FALSE(fs::exists(output)) << what;
    EXPECT_TRUE(fs::exists(fs::symlink_status(lock))) << what << ": the planted one was removed";
    fs::remove_all(lock);
  }
  // The path cleared, the batch writes.
  EXPECT_EQ(run(batch_into(images, output), temp.path() / "b.log"), 0);
}

TEST(LockFile, AReaderStartingAsAnotherEndsWaitsForItInsteadOfCallingTheFileLocked) {
  // A reader that ends (~ReadLock) holds a write lock on the lock file from its taking to the
  // close, to remove the file. Before: a reader starting then said "it is locked by a writer,
  // another process" of a file nobody writes (parallel match --pairs jobs reading one file).
  const TempFolder temp("aief_lock_file");
  const std::string file = temp.file("f.h5");
  std::ofstream(file) << "";
  const std::string lock = aief::io::lock_path_of(aief::io::resolved_path(file));
  int ready[2];
  ASSERT_EQ(::pipe(ready), 0);
  const pid_t ending = ::fork();
  if (ending == 0) {  // the ending reader, slow to remove the file
    const int fd = ::open(lock.c_str(), O_RDWR | O_CREAT, 0666);
    struct flock whole {};
    whole.l_type = F_WRLCK;
    whole.l_whence = SEEK_SET;
    if (fd < 0 || ::fcntl(fd, F_OFD_SETLK, &whole) != 0) ::_exit(2);
    [[maybe_unused]] const ssize_t wrote = ::write(ready[1], "x", 1);
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    ::unlink(lock.c_str());
    ::_exit(0);
  }
  ::close(ready[1]);
  char byte = 0;
  ASSERT_EQ(::read(ready[0], &byte, 1), 1);
  ::close(ready[0]);
  EXPECT_NO_THROW(aief::io::ReadLock{file});
  EXPECT_EQ(wait_for(ending), 0);
  EXPECT_FALSE(fs::exists(lock));  // removed by the reader that came after
}

TEST(LockFile, ALockFileHasTheUmasksMode) {
  const TempFolder temp("aief_lock_file");
  const std::string output = temp.file("out.h5");
  const mode_t before = ::umask(002);
  {
    const aief::io::OutputLock held(output);
    struct stat status {};
    ASSERT_EQ(::lstat(aief::io::lock_path_of(output).c_str(), &status), 0);
    EXPECT_EQ(status.st_mode & 0777, 0664u);  // before: 0644 whatever the umask
  }
  ::umask(before);
}

// Two members of a group (uids 65530 and 65531, group 65530) sharing a setgid folder, umask 002.
// Only root can be them; another user cannot make a second member, so the test needs root.
constexpr uid_t kFirstMember = 65530, kSecondMember = 65531;
constexpr gid_t kGroup = 65530;

fs::path group_folder(const TempFolder& temp) {
  fs::permissions(temp.path(), fs::perms::all);  // the members reach into it
  const fs::path folder = temp.path() / "group";
  fs::create_directory(folder);
  EXPECT_EQ(::chown(folder.c_str(), 0, kGroup), 0);
  EXPECT_EQ(::chmod(folder.c_str(), 02775), 0);
  return folder;
}

How as_member(uid_t uid, const TempFolder& temp) {
  How how;
  how.cli = cli_for_others(temp.path());
  how.uid = uid;
  how.gid = kGroup;
  how.umask = 002;
  return how;
}

TEST(LockFile, AGroupFoldersSecondMemberWaitsForTheFirst) {
  // Before: "cannot create its lock file ... Permission denied" (the lock was made 0644).
  if (::geteuid() != 0) GTEST_SKIP() << "two members of a group are two users: only root can be";
  const TempFolder temp("aief_lock_file");
  const fs::path folder = group_folder(temp), images = image_folder(temp.path(), "i", 3);
  fs::permissions(images, fs::perms::all);
  const fs::path output = folder / "g.h5";
  ASSERT_EQ(run(batch_into(images, output), folder / "a.log", as_member(kFirstMember, temp)), 0)
      << text_of(folder / "a.log.err");
  // The first member's writer, held here as that member (a child that holds the lock until told).
  int pipes[2];
  ASSERT_EQ(::pipe2(pipes, O_CLOEXEC), 0);  // the second member's run must not hold it open
  const pid_t first = ::fork();
  if (first == 0) {
    if (::setgroups(1, &kGroup) != 0 || ::setgid(kGroup) != 0 || ::setuid(kFirstMember) != 0)
      ::_exit(2);
    ::umask(002);
    ::close(pipes[1]);
    const aief::io::OutputLock held(output.string());
    char byte;
    [[maybe_unused]] const ssize_t got = ::read(pipes[0], &byte, 1);
    ::_exit(0);
  }
  ::close(pipes[0]);
  while (!fs::exists(aief::io::lock_path_of(output.string())))
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  const fs::path log = folder / "b.log";
  const pid_t second = start(batch_into(images, output), log, as_member(kSecondMember, temp));
  const bool waited = says_it_waits(second, log);
  ::close(pipes[1]);  // the first member's run ends
  EXPECT_EQ(wait_for(first), 0);
  EXPECT_TRUE(waited) << text_of(log.string() + ".err");
  EXPECT_EQ(wait_for(second), 0) << text_of(log.string() + ".err");
}

TEST(LockFile, AStaleLockOfAnotherMemberIsNamedWithTheCommandThatRemovesIt) {
  // Before: after a kill -9, the 0644 lock of one member blocked every other member for good.
  if (::geteuid() != 0) GTEST_SKIP() << "a lock file of another user needs root to make";
  const TempFolder temp("aief_lock_file");
  const fs::path folder = group_folder(temp), images = image_folder(temp.path(), "i", 2);
  fs::permissions(images, fs::perms::all);
  const fs::path output = folder / "g.h5", lock = aief::io::lock_path_of(output.string());
  const auto plant_stale_lock = [&] {
    std::ofstream(lock) << "process 999999 on host gone\n";
    ASSERT_EQ(::chown(lock.c_str(), kFirstMember, kGroup), 0);
    ASSERT_EQ(::chmod(lock.c_str(), 0644), 0);  // as an older aief made it
  };
  // In a sticky folder only its owner removes it: named, with the command.
  ASSERT_EQ(::chmod(folder.c_str(), 03775), 0);
  plant_stale_lock();
  const fs::path log = folder / "b.log";
  EXPECT_EQ(run(batch_into(images, output), log, as_member(kSecondMember, temp)), 1);
  const std::string said = text_of(log.string() + ".err");
  EXPECT_NE(said.find("was left by a run that has ended (process 999999 on host gone"),
            std::string::npos)
      << said;
  EXPECT_NE(said.find("it is stale and can be removed: rm -f '" + lock.string() + "'"),
            std::string::npos)
      << said;
  // Where the folder lets a member remove it, the run removes it and writes.
  ASSERT_EQ(::chmod(folder.c_str(), 02775), 0);
  EXPECT_EQ(run(batch_into(images, output), log, as_member(kSecondMember, temp)), 0)
      << text_of(log.string() + ".err");
  EXPECT_FALSE(fs::exists(lock));
}

TEST(LockFile, AWritableFileInAReadOnlyFolderSaysTheLockFileCannotBeMadeThere) {
  // Before: "cannot open 'f.h5' for writing: another handle holds it open (an h5py.File ...)".
  // Root writes in any folder: the run is another user's then (a folder of mode 0555 is
  // read-only to them), else this user's.
  const TempFolder temp("aief_lock_file");
  fs::permissions(temp.path(), fs::perms::all);
  const fs::path images = image_folder(temp.path(), "i", 2), folder = temp.path() / "ro";
  fs::permissions(images, fs::perms::all);
  fs::create_directory(folder);
  const fs::path output = folder / "f.h5";
  ASSERT_EQ(run(batch_into(images, output), temp.path() / "a.log"), 0);
  fs::permissions(output, fs::perms::all & ~fs::perms::others_exec & ~fs::perms::group_exec &
                              ~fs::perms::owner_exec);
  fs::permissions(folder, fs::perms::owner_read | fs::perms::owner_exec | fs::perms::group_read |
                              fs::perms::group_exec | fs::perms::others_read |
                              fs::perms::others_exec);
  How how;
  if (::geteuid() == 0) {
    how.cli = cli_for_others(temp.path());
    how.uid = kSecondMember;
    how.gid = kGroup;
  }
  const fs::path log = temp.path() / "b.log";
  fs::copy_file(images / "i0.png", images / "i9.png");  // something to write
  EXPECT_EQ(run(batch_into(images, output), log, how), 1);
  const std::string said = text_of(log.string() + ".err");
  EXPECT_EQ(said.find("another handle"), std::string::npos) << said;
  EXPECT_NE(said.find("cannot write '" + output.string() + "' in place: its lock file"),
            std::string::npos)
      << said;
  EXPECT_NE(said.find("cannot be made in the folder '" + folder.string() + "'"), std::string::npos)
      << said;
  EXPECT_NE(said.find("though the file itself is writable"), std::string::npos) << said;
  // The advice, followed: written in place.
  how.extra.push_back("AIEF_FILE_LOCKING=FALSE");
  EXPECT_EQ(run(batch_into(images, output), log, how), 0) << text_of(log.string() + ".err");
  fs::permissions(folder, fs::perms::all);
}

}  // namespace

#endif  // AIEF_HAVE_HDF5
