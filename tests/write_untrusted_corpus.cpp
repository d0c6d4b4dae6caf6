// Writes each hostile or unusual scene of tests/untrusted_scenes.h, its scene file alone, into a folder: the seeds
// scripts/fuzz.sh gives the fuzzer beside tests/fuzz/corpus. Usage: write_untrusted_corpus FOLDER
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "untrusted_scenes.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: write_untrusted_corpus FOLDER\n");
    return 2;
  }
  const std::filesystem::path folder = argv[1];
  std::filesystem::create_directories(folder);
  int written = 0;
  for (const rcsplat::test::UntrustedCase& c : rcsplat::test::untrusted_cases()) {
    const std::string& bytes = c.files.at(c.scene);
    if (bytes.size() > 16384) continue;  // the fuzzer's -max_len: a seed it would cut is no seed
    std::ofstream out(folder / (c.name + std::filesystem::path(c.scene).extension().string()), std::ios::binary);
    out.write(bytes.data(), std::streamsize(bytes.size()));
    ++written;
  }
  std::printf("%d seeds in %s\n", written, folder.c_str());
  return 0;
}
