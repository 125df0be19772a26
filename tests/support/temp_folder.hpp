#pragma once
// A folder of a run's own under $TMPDIR (or /tmp): removed when the run
// succeeded, kept, with its path printed, when it did not (it failed, or an
// exception left before succeeded()), so that its logs can be read. Without
// GoogleTest: the benchmarks use it as it is; TempDir (temp_dir.hpp) is it
// for a GoogleTest test.
#include <stdlib.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>

namespace ubersim::test {

class TempFolder {
 public:
  // `name` and a random suffix name the folder; `kept` is what stderr says
  // before its path when it is kept.
  explicit TempFolder(const std::string& name, std::string kept = "the run's files are kept in")
      : kept_(std::move(kept)) {
    std::string pattern = (std::filesystem::temp_directory_path() / (name + ".XXXXXX")).string();
    if (::mkdtemp(pattern.data()) == nullptr) {
      throw std::runtime_error("cannot create a temporary folder " + pattern);
    }
    root_ = pattern;
  }
  ~TempFolder() {
    if (!succeeded_) {
      std::fprintf(stderr, "%s %s\n", kept_.c_str(), root_.c_str());
      return;
    }
    std::error_code ignored;
    std::filesystem::remove_all(root_, ignored);
  }
  TempFolder(const TempFolder&) = delete;
  TempFolder& operator=(const TempFolder&) = delete;

  // The run succeeded: the folder goes when this object does.
  void succeeded() { succeeded_ = true; }

  const std::filesystem::path& root() const { return root_; }
  std::string path(const std::string& name) const { return (root_ / name).string(); }
  // Writes a file (and the folders it is in) and returns its path.
  std::string write(const std::string& name, const std::string& text) const {
    const std::filesystem::path file = root_ / name;
    std::filesystem::create_directories(file.parent_path());
    std::ofstream(file) << text;
    return file.string();
  }

 private:
  std::filesystem::path root_;
  std::string kept_;
  bool succeeded_ = false;
};

}  // namespace ubersim::test
