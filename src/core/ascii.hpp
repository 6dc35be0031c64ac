#pragma once
// ASCII character classes and case folding: the one place that decides what "case-insensitive"
// means for IEC names, keywords, units and file extensions. Only A-Z and a-z fold, whatever the
// C locale says, so results never depend on the environment. Nothing here allocates except the
// two functions that return a new std::string.
#include <string>
#include <string_view>

namespace virtcom {

constexpr bool isAsciiDigit(char c) { return c >= '0' && c <= '9'; }
constexpr bool isAsciiLetter(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); }

constexpr char asciiUpper(char c) { return c >= 'a' && c <= 'z' ? static_cast<char>(c - 'a' + 'A') : c; }
constexpr char asciiLower(char c) { return c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c; }

// The value of a digit in bases up to 36 (0-9, then A-Z in either case); -1 for anything else.
constexpr int asciiDigitValue(char c) {
  if (isAsciiDigit(c)) return c - '0';
  if (isAsciiLetter(c)) return asciiUpper(c) - 'A' + 10;
  return -1;
}

constexpr bool iequalsAscii(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (asciiUpper(a[i]) != asciiUpper(b[i])) return false;
  return true;
}

constexpr bool istartsWithAscii(std::string_view text, std::string_view prefix) {
  return text.size() >= prefix.size() && iequalsAscii(text.substr(0, prefix.size()), prefix);
}

constexpr bool iendsWithAscii(std::string_view text, std::string_view suffix) {
  return text.size() >= suffix.size() && iequalsAscii(text.substr(text.size() - suffix.size()), suffix);
}

constexpr bool isAsciiSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }

// `text` without leading and trailing blanks (space, tab, CR, LF).
constexpr std::string_view trimAscii(std::string_view text) {
  while (!text.empty() && isAsciiSpace(text.front())) text.remove_prefix(1);
  while (!text.empty() && isAsciiSpace(text.back())) text.remove_suffix(1);
  return text;
}

// Copies with every letter folded; allocates.
inline std::string asciiUpper(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = asciiUpper(c);
  return out;
}

inline std::string asciiLower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = asciiLower(c);
  return out;
}

}  // namespace virtcom
