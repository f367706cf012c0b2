// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// libFuzzer target: ground-motion records (dda.ground_motion{file = ...}).
// The first byte chooses the format (the corrected-accelerogram layout or a
// CSV), the unit, the resampling step and the baseline order; the rest is
// the file. Reading must give a motion, or a dda::Error; then the motion is
// scaled, baseline-corrected and turned into the engine's histories. A
// crash, a sanitizer report, another exception or a hang is a finding.
//
// A record's header announces its values ("%  1845  INSTRUMENT AND BASELINE
// CORRECTED DATA"): a file that holds fewer is refused as truncated. So the
// custom mutator, after libFuzzer's own mutation, usually sets that count
// to the values the mutated file holds (the record's checksum, in effect),
// so that mutations reach the spacing, the resampling and the integration
// instead of stopping at the count. Seeds: the record in data/ and small
// records of both formats (fuzz/ground_motion_seeds/). Memory is capped at
// 1 GB through the estimates' own limit (set_own_memory_limit), under
// libFuzzer's RSS limit: a resampling past it is refused, naming dt.
#include <cctype>
#include <cstdint>
#include <cstring>
#include <random>
#include <sstream>
#include <string>

#include "core/error.hpp"
#include "core/memory.hpp"
#include "loading/ground_motion.hpp"

extern "C" std::size_t LLVMFuzzerMutate(std::uint8_t* data, std::size_t size, std::size_t max_size);

namespace {

constexpr const char* kAnnouncedWords = "INSTRUMENT AND BASELINE CORRECTED DATA";

// The values of an accelerogram text (the words of its lines that do not start with %).
long count_values(const std::string& text) {
  std::istringstream in(text);
  long n = 0;
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line[0] == '%') continue;
    std::istringstream words(line);
    for (std::string w; words >> w;) ++n;
  }
  return n;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  dda::set_own_memory_limit(1e9);
  return 0;
}

extern "C" std::size_t LLVMFuzzerCustomMutator(std::uint8_t* data, std::size_t size, std::size_t max_size,
                                               unsigned int seed) {
  std::minstd_rand random(seed);
  size = LLVMFuzzerMutate(data, size, max_size);
  if (size < 2 || random() % 4 == 0) return size;
  // The header's count made to match the values (from the second byte: the
  // first is the options): the digits before "INSTRUMENT AND BASELINE ...".
  std::string text(reinterpret_cast<char*>(data) + 1, size - 1);
  const std::size_t words = text.find(kAnnouncedWords);
  if (words == std::string::npos) return size;
  const std::size_t line = text.rfind('\n', words) == std::string::npos ? 0 : text.rfind('\n', words) + 1;
  std::size_t end = words;
  while (end > line && std::isspace(static_cast<unsigned char>(text[end - 1]))) --end;
  std::size_t begin = end;
  while (begin > line && std::isdigit(static_cast<unsigned char>(text[begin - 1]))) --begin;
  if (begin == end) return size;
  text.replace(begin, end - begin, std::to_string(count_values(text)));
  if (text.size() + 1 > max_size) return size;
  std::memcpy(data + 1, text.data(), text.size());
  return text.size() + 1;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const unsigned options = data[0];
  const bool csv = options & 1;
  const auto unit = static_cast<dda::AccelerationUnit>((options >> 1) % 3);
  static constexpr double kSteps[] = {0, 0.02, 0.01, 0.005};  // 0: the record's own
  const double dt = kSteps[(options >> 3) % 4];
  const int baseline = static_cast<int>((options >> 5) % 7);
  std::istringstream in(std::string(reinterpret_cast<const char*>(data) + 1, size - 1));
  try {
    const dda::GroundMotion g = csv ? dda::GroundMotion::parse_csv(in, "fuzz.csv", unit, dt)
                                    : dda::GroundMotion::parse_accelerogram(in, "fuzz.dat", unit, dt);
    const dda::GroundMotion c = g.scaled(-1).baseline_corrected(baseline);
    (void)c.acceleration_history().value(c.duration() / 2);
    (void)c.displacement_history().double_integral(c.duration());
    (void)c.peak_velocity();
  } catch (const dda::Error&) {}
  return 0;
}
