// The tests' way into a pass: tests/pass_probe.h defines rcsplat::test::PassProbe, which a pass names as its friend
// where a test must read what no user can observe (a map's per-photon estimates, a pass's raw buffers). The product
// declares the name and ships no code for it.
#pragma once

namespace rcsplat::test {
struct PassProbe;
}  // namespace rcsplat::test
