#pragma once
// A set of output files written all or nothing (retarget --mode transfer: the user's mesh, its .mtl
// files and textures, face.rig, report.json, emotions.png).
//
//   OutputSet out("rigged");
//   out.add("face.obj", bytes);                       // paths relative to the directory, inside it
//   out.add("textures/skin.png", png_bytes);
//   out.add_writer("face.glb", [&](const std::string& p) { doc.write(p, ...); });
//   out.commit();   // every file or none (and no directory left behind that commit created)
#include <functional>
#include <string>
#include <vector>

namespace emoface::retarget {

class OutputSet {
 public:
  explicit OutputSet(std::string directory);
  /// A file with these bytes at `relative_path` ('/' separated, inside the directory: InvalidInput
  /// for an empty, absolute or `..` path, or one given twice).
  void add(const std::string& relative_path, std::string bytes);
  /// A file made by `write(path)`, which must create the file at the path it is given (a temporary
  /// name with the same extension in the same directory).
  void add_writer(const std::string& relative_path,
                  std::function<void(const std::string& path)> write);
  /// Creates the directory (and sub-directories), writes every file under a temporary name, then
  /// renames them into place. On any failure every temporary file, every file already renamed and
  /// every directory commit created is removed, and the error is rethrown; files that were there
  /// before and were not part of the set are never touched.
  void commit();
  const std::string& directory() const { return directory_; }

 private:
  struct Entry {
    std::string path;  // relative
    std::function<void(const std::string&)> write;
  };
  std::string directory_;
  std::vector<Entry> entries_;
};

}  // namespace emoface::retarget
