// A command's outputs as one set (io/atomic_file.hpp): what commit() leaves in the folder (the new files, other
// commands' files and subfolders, none of the command's own earlier files it did not write again), a set not
// committed leaves the folder as it was, a command reads its own staged files, and folders that cannot take a set
// are refused in one line. A file written beside the command (write_beside) is in the set when it is brought in; a
// writer that fails leaves the folder as it was.
#include <gtest/gtest.h>

#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>

#include "common/error.hpp"
#include "io/atomic_file.hpp"

namespace sw {
namespace {

namespace fs = std::filesystem;

fs::path fresh_root(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("sw_output_set_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::string text_of(const fs::path& p) {
  std::ifstream in(p);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::set<std::string> names_in(const fs::path& folder) {
  std::set<std::string> names;
  for (const auto& e : fs::directory_iterator(folder)) names.insert(e.path().filename().string());
  return names;
}

/// A folder as an earlier fem run and another command left it.
fs::path earlier_folder(const fs::path& root) {
  const fs::path dir = root / "case";
  fs::create_directories(dir / "sub");
  for (const char* f : {"result.json", "flexspline.pvd", "flexspline_generator.vtu", "flexspline_torque.vtu"})
    write_file_atomic(dir / f, "earlier");
  write_file_atomic(dir / "backlash.json", "another command's");
  write_file_atomic(dir / "sub" / "kept.txt", "in a subfolder");
  return dir;
}

const std::vector<std::string> kFem = {"result.json", "neutral_curve.csv", "flexspline.pvd", "flexspline_*.vtu"};

TEST(OutputSet, CommitKeepsOtherFilesAndDropsOwnFilesNotWrittenAgain) {
  const fs::path root = fresh_root("commit");
  const fs::path dir = earlier_folder(root);
  OutputSet out(dir, kFem);
  write_file_atomic(out.staging() / "result.json", "new");
  write_file_atomic(out.staging() / "flexspline_torque.vtu", "new");
  write_file_atomic(out.staging() / "flexspline.pvd", "new");
  EXPECT_EQ(text_of(dir / "result.json"), "earlier");  // nothing shows before the commit
  out.commit();
  EXPECT_EQ(names_in(dir), (std::set<std::string>{"backlash.json", "flexspline.pvd", "flexspline_torque.vtu",
                                                  "result.json", "sub"}));
  EXPECT_EQ(text_of(dir / "result.json"), "new");
  EXPECT_EQ(text_of(dir / "backlash.json"), "another command's");
  EXPECT_EQ(text_of(dir / "sub" / "kept.txt"), "in a subfolder");
  EXPECT_EQ(names_in(root), std::set<std::string>{"case"});  // no staging folder, no earlier folder left
  fs::remove_all(root);
}

TEST(OutputSet, WithoutCommitTheFolderStaysAsItWasAndTheStagingGoes) {
  const fs::path root = fresh_root("abandon");
  const fs::path dir = earlier_folder(root);
  const std::set<std::string> before = names_in(dir);
  {
    OutputSet out(dir, kFem);
    write_file_atomic(out.staging() / "result.json", "new");
  }
  EXPECT_EQ(names_in(dir), before);
  EXPECT_EQ(text_of(dir / "result.json"), "earlier");
  EXPECT_EQ(names_in(root), std::set<std::string>{"case"});
  {
    OutputSet out(root / "never");  // a folder that did not exist is not made
    write_file_atomic(out.staging() / "result.json", "new");
  }
  EXPECT_FALSE(fs::exists(root / "never"));
  fs::remove_all(root);
}

TEST(OutputSet, AFileWrittenBesideIsInTheSetAndAFailedOneKeepsTheFolder) {
  const fs::path root = fresh_root("beside");
  const fs::path dir = earlier_folder(root);
  {
    OutputSet out(dir, kFem);
    out.write_beside([staging = out.staging()] {
      std::this_thread::sleep_for(std::chrono::milliseconds(300));  // still writing when the command commits
      write_file_atomic(staging / "flexspline_torque.vtu", "new");
    });
    write_file_atomic(out.staging() / "result.json", "new");
    out.commit();
  }
  EXPECT_EQ(text_of(dir / "flexspline_torque.vtu"), "new");
  EXPECT_EQ(text_of(dir / "result.json"), "new");
  const std::set<std::string> before = names_in(dir);
  {
    OutputSet out(dir, kFem);
    out.write_beside([] { throw InputError("out/case/flexspline_torque.vtu: cannot write"); });
    write_file_atomic(out.staging() / "result.json", "newer");
    EXPECT_THROW(
        {
          try {
            out.commit();
          } catch (const InputError& e) {
            EXPECT_STREQ(e.what(), "out/case/flexspline_torque.vtu: cannot write");
            throw;
          }
        },
        InputError);
  }
  EXPECT_EQ(names_in(dir), before);
  EXPECT_EQ(text_of(dir / "result.json"), "new");
  {  // a set given up while its writer runs: the destructor waits for it before the staging folder goes
    OutputSet out(dir, kFem);
    out.write_beside([staging = out.staging()] {
      std::this_thread::sleep_for(std::chrono::milliseconds(300));
      write_file_atomic(staging / "flexspline_generator.vtu", "never seen");
    });
  }
  EXPECT_EQ(names_in(dir), before);
  EXPECT_EQ(names_in(root), std::set<std::string>{"case"});  // no staging folder left
  fs::remove_all(root);
}

TEST(OutputSet, ANewFolderAppearsWithTheSetAndOwnsWhatJobsAdd) {
  const fs::path root = fresh_root("new");
  OutputSet out(root / "a" / "b");
  out.own({"contact.json"});
  write_file_atomic(out.staging() / "contact.json", "new");
  out.commit();
  EXPECT_EQ(names_in(root / "a" / "b"), std::set<std::string>{"contact.json"});
  EXPECT_EQ(names_in(root / "a"), std::set<std::string>{"b"});
  fs::remove_all(root);
}

TEST(OutputSet, ACommandReadsItsOwnStagedFilesAndOthersWhereTheyAre) {
  const fs::path root = fresh_root("read");
  const fs::path dir = earlier_folder(root);
  OutputSet out(dir, kFem);
  write_file_atomic(out.staging() / "result.json", "new");
  EXPECT_EQ(text_of(out.read_path(dir / "result.json")), "new");
  EXPECT_EQ(text_of(out.read_path(dir / "backlash.json")), "another command's");
  EXPECT_EQ(out.read_path(root / "elsewhere.json"), root / "elsewhere.json");
  fs::remove_all(root);
}

TEST(OutputSet, RefusesTheWorkingDirectoryAFileAndAboveInOneLine) {
  const fs::path root = fresh_root("refuse");
  const fs::path here = fs::current_path();
  fs::current_path(root);
  try {
    OutputSet out(".");
    ADD_FAILURE() << "the working directory was taken";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("the working directory or above it"), std::string::npos) << e.what();
  }
  EXPECT_THROW(OutputSet(".."), InputError);
  write_file_atomic(root / "file", "x");
  try {
    OutputSet out(root / "file");
    ADD_FAILURE() << "a file was taken as a folder";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("not a folder"), std::string::npos) << e.what();
  }
  fs::current_path(here);
  EXPECT_EQ(names_in(root), std::set<std::string>{"file"});
  fs::remove_all(root);
}

}  // namespace
}  // namespace sw
