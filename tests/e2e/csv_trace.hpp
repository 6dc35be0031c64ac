#pragma once
// Reading the `--csv` trace of `virtcom run` (time_s,signal,value rows of the changes, in time
// order, every signal's initial value first) in the e2e tests.
#include <sstream>
#include <string>
#include <vector>

// One recorded change: virtual time (s) and the new value.
struct Change {
  double timeS;
  double value;
};

// Every change the CSV records for `signal`, in time order (the initial value first).
inline std::vector<Change> changes(const std::string& csv, const std::string& signal) {
  std::vector<Change> out;
  std::istringstream in(csv);
  for (std::string line; std::getline(in, line);) {
    const size_t a = line.find(',');
    const size_t b = line.find(',', a + 1);
    if (a == std::string::npos || b == std::string::npos || line.substr(a + 1, b - a - 1) != signal) continue;
    out.push_back({std::stod(line.substr(0, a)), std::stod(line.substr(b + 1))});
  }
  return out;
}

// Every value the CSV records for `signal`, in time order (the initial value first).
inline std::vector<double> values(const std::string& csv, const std::string& signal) {
  std::vector<double> out;
  for (const Change& c : changes(csv, signal)) out.push_back(c.value);
  return out;
}
