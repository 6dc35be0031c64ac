// libFuzzer target for UNIVERSAL_AXIS mapping files (lib/mappings/*.yaml, read by the cell
// loader from a user's `mapping:` key): YAML text -> ConfigNode -> parseMapping. A mapping that
// validates is then applied as in a run: block values derived from the input are packed into the
// output image, and the input bytes themselves are decoded as the drive's reply image and
// unpacked, in both directions of the telegram codec. Finds crashes, out-of-range bit/word
// accesses and UB (shifts, float -> int) in the parser, the validator, the runtime and the codec.
#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <iterator>
#include <limits>
#include <string>

#include "cell/yaml_config.hpp"
#include "drives/axis_mapping.hpp"

namespace drives = virtcom::drives;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  virtcom::SourceManager sources;
  virtcom::Diagnostics diags;
  virtcom::ConfigNode root;
  if (!virtcom::cell::parseYaml("fuzz.yaml", text, sources, diags, root)) return 0;
  auto spec = drives::parseMapping(root, diags);
  if (!spec) {
    if (!diags.hasErrors()) __builtin_trap();  // a rejected mapping always says why
    return 0;
  }
  // Arbitrary bytes for the images; block values (a PLC writes any REAL) picked by those bytes.
  std::array<uint8_t, drives::kMaxImageBytes> image{};
  std::memcpy(image.data(), data, std::min(size, image.size()));
  static constexpr double kValues[] = {0, 1, -1, 0.5, 2.5, 32767.5, -32768.5, 1e9, -1e12, 1e300,
                                       std::numeric_limits<double>::infinity(), std::numeric_limits<double>::quiet_NaN()};
  drives::AxisSignalValues values{};
  for (size_t i = 0; i < values.size(); ++i) values[i] = kValues[image[i % image.size()] % std::size(kValues)];
  drives::MappingRuntime runtime(*spec);
  drives::RawWords words{}, rx{};
  for (int tick = 0; tick < 3; ++tick) {
    runtime.pack(values, words);
    runtime.toWire(words, image);
    drives::decode(spec->telegram, drives::Dir::ToDrive, image, rx);
    drives::encode(spec->telegram, drives::Dir::FromDrive, rx, image);
    runtime.fromWire(image, words);
    runtime.unpack(words, values);
  }
  return 0;
}
