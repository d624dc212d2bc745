#pragma once
// Every byte the glTF loader reads from disk passes through here: the scene file itself and
// the external buffers and images its URIs name (tinygltf is routed here by its FsCallbacks).
#include <tiny_gltf.h>

#include <cstdint>
#include <string>
#include <vector>

namespace tray {

/// Largest file the loader reads (the scene, a buffer or an image). tinygltf 2.7.0 has no cap.
constexpr uint64_t kMaxFileBytes = uint64_t(2) << 30;
/// Largest total a scene's URIs may read: many buffers may name the same big file.
constexpr uint64_t kMaxUriBytes = uint64_t(4) << 30;

/// Reads a whole regular file of at most `limit` bytes. Devices, FIFOs and directories are
/// refused, since reading them may block forever or never end. Returns false with `problem`.
bool readRegularFile(const std::string& path, std::vector<unsigned char>& out, std::string& problem,
                     uint64_t limit = kMaxFileBytes);

/// Decides which URIs a scene may read (docs/scene-format.md, "Validation"): relative paths
/// inside the scene's folder only, unless allowAnyPath; never a scheme other than data:.
class UriPolicy {
 public:
  /// `folder`: the scene file's folder (made canonical here).
  UriPolicy(const std::string& folder, bool allowAnyPath);
  /// Refuses every URI: for documents loaded from memory, which have no folder.
  static UriPolicy noFiles();
  bool allowsFiles() const { return allowsFiles_; }
  const std::string& folder() const { return folder_; }
  /// Canonical path of the regular file a percent-decoded URI names, or "" with `problem`.
  std::string resolve(const std::string& uri, std::string& problem) const;

 private:
  std::string folder_;
  bool allowAnyPath_;
  bool allowsFiles_ = true;
};

/// tinygltf file callbacks enforcing a UriPolicy. tinygltf reports a refused file only as "File
/// not found", so the first specific refusal is kept here for the error message.
class FileAccess {
 public:
  explicit FileAccess(const UriPolicy& policy) : policy_(policy) {}
  FileAccess(const FileAccess&) = delete;
  FileAccess& operator=(const FileAccess&) = delete;
  /// Callbacks bound to this object; it must outlive the TinyGLTF that uses them.
  tinygltf::FsCallbacks callbacks();
  /// The first refusal, e.g. "URI '../x.bin' leaves the scene folder"; empty if none.
  const std::string& firstProblem() const { return firstProblem_; }

 private:
  static bool fileExists(const std::string& path, void* self);
  static std::string expandFilePath(const std::string& path, void* self);
  static bool readWholeFile(std::vector<unsigned char>* out, std::string* err,
                            const std::string& path, void* self);
  static bool writeWholeFile(std::string* err, const std::string& path,
                             const std::vector<unsigned char>& contents, void* self);
  /// The URI part of a path tinygltf built as folder + "/" + uri; false for its second guess,
  /// "./" + uri relative to the working directory, which TRay never allows.
  bool uriOf(const std::string& path, std::string& uri) const;
  std::string resolve(const std::string& path);
  void record(const std::string& problem);

  const UriPolicy& policy_;
  std::string firstProblem_;
  uint64_t bytesRead_ = 0;
};

}  // namespace tray
