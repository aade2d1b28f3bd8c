// Output files are written whole or not at all: each goes to a sibling temp file, and a
// command's outputs are renamed into place together once every one of them is written.
#pragma once

#include <cstddef>
#include <fstream>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace strand::slicer {

// Largest input file read whole (G-code, SVG, JSON, meshes): bounds memory before any work.
inline constexpr std::size_t kMaxInputBytes = std::size_t{256} << 20;

// The outputs of one command as a transaction. stage() writes a temp file beside the target
// ("<target>.strand-tmp", so a re-run replaces a killed run's leftover); commit() renames
// every staged file into place; an uncommitted set removes its temps when destroyed, and
// temps are removed on SIGINT/SIGTERM/SIGHUP too (install_signal_cleanup). A set of several
// files is committed through a journal beside its first file, written before the first
// rename and removed after the last, with those signals held meanwhile: a set killed between
// two renames (SIGKILL, power loss) is completed by the next run that stages its first file,
// so a set is never left half old and half new for Strand. Throws InputError naming the path
// when a target cannot be written, is staged twice, or is a protected input.
class OutputFiles {
 public:
  OutputFiles() = default;
  OutputFiles(const OutputFiles&) = delete;
  OutputFiles& operator=(const OutputFiles&) = delete;
  ~OutputFiles();

  // Refuses any later output that is this file (a job file must not be overwritten by its
  // own report). Missing files are fine.
  void protect_input(const std::string& path);
  void stage(const std::string& path, const std::string& content);
  // Stages `path` to be written in pieces (large G-code streams into it as it is formatted,
  // so the whole file never sits in memory): returns the temp file's stream, valid until
  // commit(), which flushes it and throws InputError if any write failed.
  std::ostream& stage_stream(const std::string& path);
  // Text that goes before what was streamed into `path` (a file whose first lines are known
  // only once its body is written, like G-code headers with totals). At commit the file is
  // put together in the kernel (copy_file_range), without reading the body back.
  void prepend(const std::string& path, std::string head);
  void commit();
  // Test hook: called before each rename of commit() with the number done so far.
  void on_rename(std::function<void(std::size_t)> hook) { rename_hook_ = std::move(hook); }

 private:
  struct Staged {
    std::string target, temp;
    std::unique_ptr<std::ofstream> stream;  // stage_stream only
    std::string head;                        // prepend only
  };
  void check_target(const std::string& path) const;
  std::vector<Staged> staged_;
  std::vector<std::string> protected_;
  bool committed_ = false;
  std::function<void(std::size_t)> rename_hook_;
};

// Completes the output set whose first file is `first_target` if a run was killed while
// renaming it into place (its journal, "<first_target>.strand-commit", is still there): the
// remaining finished temps are renamed and the journal removed, so the set is all new.
// Returns whether anything was renamed. stage() calls it for every target.
bool recover_output_set(const std::string& first_target);

// One output file as a transaction of its own.
void write_file_atomic(const std::string& path, const std::string& content);
// Reads a whole regular file of at most kMaxInputBytes; throws InputError naming the path
// if it is missing, a directory, unreadable or too large.
std::string read_file(const std::string& path);
// Removes the temp files of unfinished transactions when the process gets SIGINT,
// SIGTERM or SIGHUP, then dies of that signal. Call once from main().
void install_signal_cleanup();

}  // namespace strand::slicer
