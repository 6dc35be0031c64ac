#pragma once
// The content hashes of the caches (AOT objects, compiled modules): FNV-1a 64, cheap and stable
// across builds and machines. Not a defence against a chosen collision: the caches trust their
// folder as they trust the binary that writes it.
#include <cstdint>
#include <string>
#include <string_view>

namespace virtcom {

inline constexpr uint64_t kHashSeed = 0xcbf29ce484222325ull;
// `seed`: the hash of what came before, to hash several pieces as if they were one text.
uint64_t hashText(std::string_view text, uint64_t seed = kHashSeed);
// hashText as 16 lower-case hex digits (file names, index entries).
std::string hashHex(std::string_view text);

}  // namespace virtcom
