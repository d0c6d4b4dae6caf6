// Every class of hostile or unusual scene file (tests/untrusted_scenes.h), run through the real binary as a user
// would: `rcsplat render SCENE -o out.exr -o out.png --json out.json` in a working folder of its own. A refusal must
// exit non-zero, say the case's key words (the file, the object, the defect), reveal nothing it must not, and leave no
// output; a valid file must render. Where an allocation bomb is the point, the process's peak resident memory is
// checked too (not under AddressSanitizer, whose own memory is larger than the ceilings).
#include "untrusted_scenes.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "test_support.h"

namespace rcsplat {
namespace {

namespace fs = std::filesystem;
using test::UntrustedCase;

#if defined(__SANITIZE_ADDRESS__)
constexpr bool kSanitized = true;
#else
constexpr bool kSanitized = false;
#endif

class UntrustedScene : public ::testing::TestWithParam<UntrustedCase> {};

TEST_P(UntrustedScene, IsRefusedClearlyOrRendered) {
  const UntrustedCase& c = GetParam();
  const fs::path folder = fs::path(test::scratch_dir()) / "case";
  test::write_untrusted_case(c, folder);
  const fs::path work = folder / "work";
  fs::create_directories(work);
  if (!c.working_folder_file.empty()) {
    // The same quad's buffer, where only a retry relative to the working folder would find it.
    fs::copy_file(folder / "scene/quad.bin", work / c.working_folder_file);
  }
  std::vector<std::string> args = {"render",
                                   (folder / c.scene).string(),
                                   "-o",
                                   "out.exr",
                                   "-o",
                                   "out.png",
                                   "--json",
                                   "out.json",
                                   "--width",
                                   "24",
                                   "--height",
                                   "16",
                                   "--pixel-samples",
                                   "1"};
  for (std::string a : c.args) {
    const size_t at = a.find("{case}");
    if (at != std::string::npos) a.replace(at, 6, folder.string());
    args.push_back(a);
  }
  const test::CommandRun run = test::run_rcsplat(work.string(), args, 300);
  const bool outputs = fs::exists(work / "out.exr") || fs::exists(work / "out.png") || fs::exists(work / "out.json");
  if (c.renders) {
    EXPECT_EQ(run.exit_code, 0) << run.output;
    EXPECT_TRUE(fs::exists(work / "out.exr") && fs::exists(work / "out.png") && fs::exists(work / "out.json"))
        << run.output;
  } else {
    EXPECT_EQ(run.exit_code, 1) << run.output;
    EXPECT_FALSE(outputs) << "a refused scene left output behind\n" << run.output;
    // A refusal names the scene file it refuses.
    EXPECT_NE(run.output.find(fs::path(c.scene).filename().string()), std::string::npos) << run.output;
  }
  for (const std::string& word : c.key_words)
    EXPECT_NE(run.output.find(word), std::string::npos) << word << "\n" << run.output;
  for (const std::string& word : c.absent_words)
    EXPECT_EQ(run.output.find(word), std::string::npos) << word << "\n" << run.output;
  // No library's internals in what a user reads.
  for (const char* internal :
       {"vector::", "unknown error", "STB", "stbi", "tinygltf", "json.exception", "basic_string"})
    EXPECT_EQ(run.output.find(internal), std::string::npos) << internal << "\n" << run.output;
  if (c.memory_ceiling_mib && !kSanitized) {
    EXPECT_LT(run.peak_memory_kib, long(c.memory_ceiling_mib) * 1024) << "peak resident memory, KiB";
    std::printf("peak resident memory %.0f MiB (ceiling %d MiB)\n", double(run.peak_memory_kib) / 1024.0,
                c.memory_ceiling_mib);
  }
}

INSTANTIATE_TEST_SUITE_P(Cases, UntrustedScene, ::testing::ValuesIn(test::untrusted_cases()),
                         [](const ::testing::TestParamInfo<UntrustedCase>& info) { return info.param.name; });

// The two symbolic-link refusals read the same whether the link's target exists or not: nothing tells which.
TEST(UntrustedScenePolicy, ARefusalDoesNotTellWhetherAFileOutsideExists) {
  std::map<std::string, std::string> messages;
  for (const UntrustedCase& c : test::untrusted_cases()) {
    if (c.name != "SymbolicLinkLeadingOut" && c.name != "SymbolicLinkLeadingOutToNothing") continue;
    const fs::path folder = fs::path(test::scratch_dir()) / "same";  // one folder: the paths in the messages agree
    fs::remove_all(folder);
    test::write_untrusted_case(c, folder);
    fs::create_directories(folder / "work");
    messages[c.name] =
        test::run_rcsplat((folder / "work").string(), {"info", (folder / c.scene).string()}, 120).output;
  }
  ASSERT_EQ(messages.size(), 2u);
  EXPECT_EQ(messages["SymbolicLinkLeadingOut"], messages["SymbolicLinkLeadingOutToNothing"]);
}

}  // namespace
}  // namespace rcsplat
