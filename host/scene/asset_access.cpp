#include "scene/asset_access.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>

#include "util/error.h"

namespace rcsplat {
namespace fs = std::filesystem;

namespace {

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// p lies in root or below it; both lexically normal and absolute.
bool within(const fs::path& p, const fs::path& root) {
  auto r = root.begin(), q = p.begin();
  for (; r != root.end(); ++r, ++q) {
    if (r->empty()) continue;  // the empty last element of a root ending in '/'
    if (q == p.end() || *q != *r) return false;
  }
  return true;
}

// p with every symbolic link in it followed, dangling ones too (std::filesystem's canonical forms stop at a link
// whose target is missing, which would make a link that leads out look like a missing file inside).
fs::path follow_links(fs::path p, const std::string& name) {
  for (int links = 0; links < 40; ++links) {
    fs::path prefix;
    bool followed = false;
    for (auto part = p.begin(); part != p.end(); ++part) {
      prefix /= *part;
      std::error_code ec;
      if (!fs::is_symlink(fs::symlink_status(prefix, ec))) continue;
      const fs::path target = fs::read_symlink(prefix, ec);
      if (ec) throw Error(name + ": a symbolic link on its path cannot be read");
      fs::path rest;
      for (auto after = std::next(part); after != p.end(); ++after) rest /= *after;
      p = ((target.is_absolute() ? target : prefix.parent_path() / target) / rest).lexically_normal();
      followed = true;
      break;
    }
    if (!followed) return p;
  }
  throw Error(name + ": more than 40 symbolic links on its path");
}

}  // namespace

AssetAccess::AssetAccess(const std::string& scene_file, const std::vector<std::string>& extra_roots)
    : scene_file_(scene_file) {
  std::error_code ec;
  fs::path file = fs::canonical(scene_file, ec);
  if (ec) throw Error(scene_file + ": cannot be opened");
  roots_.push_back(file.parent_path());
  for (const std::string& root : extra_roots) {
    fs::path canonical = fs::canonical(root, ec);
    if (ec || !fs::is_directory(canonical, ec)) throw Error("--asset-root " + root + ": not a folder");
    roots_.push_back(canonical);
  }
}

std::string AssetAccess::decode_uri(const std::string& uri) {
  std::string out;
  out.reserve(uri.size());
  for (size_t i = 0; i < uri.size(); ++i) {
    int hi = 0, lo = 0;
    if (uri[i] == '%' && i + 2 < uri.size() && (hi = hex_digit(uri[i + 1])) >= 0 && (lo = hex_digit(uri[i + 2])) >= 0) {
      out += char(hi * 16 + lo);
      i += 2;
    } else {
      out += uri[i];
    }
  }
  return out;
}

bool AssetAccess::inside_a_root(const fs::path& p) const {
  return std::any_of(roots_.begin(), roots_.end(), [&](const fs::path& root) { return within(p, root); });
}

std::string AssetAccess::rule() const {
  std::string text = "a scene reads only files inside its own folder (" + roots_.front().string() + ")";
  for (size_t i = 1; i < roots_.size(); ++i) text += (i == 1 ? " and inside --asset-root " : ", ") + roots_[i].string();
  if (roots_.size() == 1) text += "; --asset-root DIR lets a trusted scene read inside DIR too";
  return text;
}

fs::path AssetAccess::resolve(const std::string& what, const std::string& uri) const {
  const std::string name = scene_file_ + ": " + what + " '" + uri + "'";
  if (uri.empty()) throw Error(scene_file_ + ": " + what + " has an empty uri");
  // A scheme (RFC 3986: a letter, then letters, digits, '+', '-' or '.', then ':') before any '/'.
  const size_t colon = uri.find(':');
  if (colon != std::string::npos && colon > 0 && std::isalpha(static_cast<unsigned char>(uri[0])) &&
      uri.find('/') > colon && std::all_of(uri.begin(), uri.begin() + long(colon), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '+' || c == '-' || c == '.';
      })) {
    std::string scheme = uri.substr(0, colon);
    std::transform(scheme.begin(), scheme.end(), scheme.begin(), [](char c) { return char(std::tolower(c)); });
    if (scheme == "file") throw Error(name + ": file: URIs are not read (" + rule() + ", named by relative paths)");
    throw Error(name + ": the URI scheme '" + scheme +
                ":' is not read; rcsplat reads data: URIs and relative paths "
                "to files inside the scene's folder, nothing over a network");
  }
  const std::string decoded = decode_uri(uri);
  if (decoded.find('\0') != std::string::npos) throw Error(name + ": the path holds a NUL character");
  if (!decoded.empty() && (decoded[0] == '/' || decoded[0] == '\\'))
    throw Error(name + ": absolute paths are not read (" + rule() + ", named by relative paths)");
  const fs::path lexical = (roots_.front() / decoded).lexically_normal();
  if (!inside_a_root(lexical)) throw Error(name + ": the path leaves the scene's folder (" + rule() + ")");
  // Symbolic links inside the folder are followed before the check; one that leads out is refused the same way
  // whether its target exists or not.
  const fs::path real = follow_links(lexical, name);
  if (!inside_a_root(real)) throw Error(name + ": a symbolic link leads out of the scene's folder (" + rule() + ")");
  std::error_code ec;
  const fs::file_status status = fs::status(real, ec);
  if (ec || status.type() == fs::file_type::not_found) throw Error(name + ": no such file in the scene's folder");
  if (status.type() != fs::file_type::regular) throw Error(name + ": not a regular file");
  return real;
}

std::vector<unsigned char> AssetAccess::read(const fs::path& file, uint64_t bytes, const std::string& what) const {
  const std::string name = scene_file_ + ": " + what + " (" + file.string() + ")";
  // O_NOFOLLOW: resolve() returned a path without links; one put in its place since is not followed.
  const int fd = ::open(file.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) throw Error(name + ": cannot be opened");
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    throw Error(name + ": not a regular file");
  }
  if (uint64_t(st.st_size) < bytes) {
    ::close(fd);
    throw Error(name + ": holds " + std::to_string(st.st_size) + " bytes, " + std::to_string(bytes) +
                " expected: the file is truncated");
  }
  std::vector<unsigned char> out(bytes);
  size_t done = 0;
  while (done < bytes) {
    const ssize_t got = ::read(fd, out.data() + done, bytes - done);
    if (got <= 0) {
      ::close(fd);
      throw Error(name + ": cannot be read (it ended at byte " + std::to_string(done) + ")");
    }
    done += size_t(got);
  }
  ::close(fd);
  return out;
}

}  // namespace rcsplat
