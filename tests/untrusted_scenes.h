// Malformed, hostile and unusual glTF files, one for each class of defect docs/SECURITY.md names: files outside the
// scene's folder, exponential or deep node graphs, allocation bombs, messages that must name the object, and valid
// files that must render. Written by code here (nothing downloaded); used by tests/untrusted_scenes_test.cpp, which
// runs the real binary on each, and by scripts/fuzz.sh, which seeds the fuzzer with them.
#pragma once
#include <filesystem>
#include <map>
#include <ostream>
#include <string>
#include <vector>

namespace rcsplat::test {

struct UntrustedCase {
  std::string name;
  // Files under the case's folder, by relative path; the scene and its own files live in scene/, and secret.bin
  // beside scene/ stands for a file the scene must not read.
  std::map<std::string, std::string> files;
  std::map<std::string, std::string> symlinks;  // link (relative to the case folder) -> target, as written
  std::string scene = "scene/scene.gltf";
  // Extra command-line arguments; "{case}" stands for the case's folder.
  std::vector<std::string> args;
  bool renders = false;                   // valid input: exit 0 and every output written
  std::vector<std::string> key_words;     // each in what the binary prints (the refusal, or a warning)
  std::vector<std::string> absent_words;  // none in what it prints (what a refusal must not reveal)
  int memory_ceiling_mib = 0;             // the process's peak resident memory stays below; 0: not checked
  std::string working_folder_file;        // a file of this name put in the working folder (the retry there)
};

std::vector<UntrustedCase> untrusted_cases();
inline void PrintTo(const UntrustedCase& c, std::ostream* os) { *os << c.name; }  // gtest names a failing case

// Writes the case's files and links under folder (created).
void write_untrusted_case(const UntrustedCase& c, const std::filesystem::path& folder);

}  // namespace rcsplat::test
