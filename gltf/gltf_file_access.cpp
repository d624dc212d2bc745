#include "gltf/gltf_file_access.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cstdlib>
#include <cstring>

namespace tray {

bool readRegularFile(const std::string& path, std::vector<unsigned char>& out, std::string& problem,
                     uint64_t limit) {
  // O_NONBLOCK: opening a FIFO must not wait for a writer; fstat then refuses it.
  int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) {
    problem = errno == ENOENT ? "file not found" : std::string("cannot open: ") + strerror(errno);
    return false;
  }
  struct stat st{};
  bool ok = false;
  if (::fstat(fd, &st) != 0) {
    problem = std::string("cannot stat: ") + strerror(errno);
  } else if (!S_ISREG(st.st_mode)) {
    problem = "not a regular file";
  } else if (uint64_t(st.st_size) > limit) {
    problem = limit == kMaxFileBytes
                  ? "file is larger than the 2 GiB limit"
                  : "file would exceed the " + std::to_string(kMaxUriBytes >> 30) +
                        " GiB limit on all bytes a scene's URIs read";
  } else {
    out.resize(size_t(st.st_size));
    size_t done = 0;
    ok = true;
    while (done < out.size()) {
      ssize_t n = ::read(fd, out.data() + done, out.size() - done);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        problem = "read error (file changed while reading?)";
        ok = false;
        break;
      }
      done += size_t(n);
    }
  }
  ::close(fd);
  return ok;
}

namespace {

std::string canonical(const std::string& path) {
  char buffer[PATH_MAX];
  return ::realpath(path.c_str(), buffer) ? std::string(buffer) : std::string();
}

bool hasDotDotSegment(const std::string& uri) {
  size_t start = 0;
  while (start <= uri.size()) {
    size_t end = uri.find_first_of("/\\", start);
    if (end == std::string::npos) end = uri.size();
    if (uri.compare(start, end - start, "..") == 0 && end - start == 2) return true;
    start = end + 1;
  }
  return false;
}

}  // namespace

UriPolicy::UriPolicy(const std::string& folder, bool allowAnyPath)
    : folder_(canonical(folder.empty() ? "." : folder)), allowAnyPath_(allowAnyPath) {}

UriPolicy UriPolicy::noFiles() {
  UriPolicy p("/", false);
  p.folder_.clear();
  p.allowsFiles_ = false;
  return p;
}

std::string UriPolicy::resolve(const std::string& uri, std::string& problem) const {
  const std::string quoted = "URI '" + uri + "'";
  if (!allowsFiles_) {
    problem = quoted + " refused: a scene loaded from memory may only use data: URIs";
    return "";
  }
  if (uri.empty()) {
    problem =
        "a buffer or image has an empty or missing 'uri' (only a .glb's BIN chunk may "
        "stand in for it)";
    return "";
  }
  if (uri.find('\0') != std::string::npos) {
    problem = "URI contains a NUL character";
    return "";
  }
  // RFC 3986 §4.2: a relative reference's first segment has no ':', so one there is a scheme.
  size_t colon = uri.find(':'), slash = uri.find('/');
  if (colon != std::string::npos && (slash == std::string::npos || colon < slash)) {
    problem = uri.rfind("data:", 0) == 0
                  ? "malformed data: URI (expected data:<mime>;base64,<data>)"
                  : quoted + " has a scheme; only data: URIs and relative paths are allowed";
    return "";
  }
  bool absolute = uri[0] == '/' || uri[0] == '\\';
  if (!allowAnyPath_ && absolute) {
    problem = quoted + " is an absolute path; only paths relative to the scene are allowed";
    return "";
  }
  if (!allowAnyPath_ && hasDotDotSegment(uri)) {
    problem = quoted + " contains '..'; files must lie inside the scene's folder";
    return "";
  }
  if (folder_.empty()) {
    problem = "cannot resolve the scene's folder";
    return "";
  }
  std::string real = canonical(absolute ? uri : folder_ + "/" + uri);
  if (real.empty()) {
    problem = quoted + ": file not found";
    return "";
  }
  // Symbolic links may still point outside: the canonical path decides.
  std::string inside = folder_ == "/" ? folder_ : folder_ + "/";
  if (!allowAnyPath_ && real.compare(0, inside.size(), inside) != 0) {
    problem = quoted + " resolves outside the scene's folder";
    return "";
  }
  struct stat st{};
  if (::stat(real.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) {
    problem = quoted + " is not a regular file";
    return "";
  }
  return real;
}

tinygltf::FsCallbacks FileAccess::callbacks() {
  return {&FileAccess::fileExists, &FileAccess::expandFilePath, &FileAccess::readWholeFile,
          &FileAccess::writeWholeFile, this};
}

bool FileAccess::uriOf(const std::string& path, std::string& uri) const {
  const std::string& folder = policy_.folder();
  std::string prefix = !folder.empty() && folder.back() == '/' ? folder : folder + "/";
  if (folder.empty() || path.compare(0, prefix.size(), prefix) != 0) return false;
  uri = path.substr(prefix.size());
  return true;
}

void FileAccess::record(const std::string& problem) {
  if (firstProblem_.empty()) firstProblem_ = problem;
}

std::string FileAccess::resolve(const std::string& path) {
  std::string uri, problem;
  if (!policy_.allowsFiles()) {  // no folder: tinygltf passes the bare URI
    policy_.resolve(path, problem);
    record(problem);
    return "";
  }
  if (!uriOf(path, uri)) return "";  // tinygltf's working-directory guess: refused silently
  std::string real = policy_.resolve(uri, problem);
  if (real.empty()) record(problem);
  return real;
}

bool FileAccess::fileExists(const std::string& path, void* self) {
  return !static_cast<FileAccess*>(self)->resolve(path).empty();
}

// tinygltf's default expands `~` and environment variables: a file must not do that.
std::string FileAccess::expandFilePath(const std::string& path, void*) {
  return path;
}

bool FileAccess::readWholeFile(std::vector<unsigned char>* out, std::string* err,
                               const std::string& path, void* self) {
  auto* access = static_cast<FileAccess*>(self);
  std::string real = access->resolve(path), problem;
  if (real.empty()) return false;
  const uint64_t left = kMaxUriBytes - access->bytesRead_;
  if (!readRegularFile(real, *out, problem, std::min(kMaxFileBytes, left))) {
    std::string uri;
    access->uriOf(path, uri);
    access->record("URI '" + uri + "': " + problem);
    if (err) *err += problem;
    return false;
  }
  access->bytesRead_ += out->size();
  return true;
}

bool FileAccess::writeWholeFile(std::string* err, const std::string&,
                                const std::vector<unsigned char>&, void*) {
  if (err) *err += "the loader never writes files";
  return false;
}

}  // namespace tray
