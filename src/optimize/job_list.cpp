// Candidate -> job list: waits derived from precedence and resources, the behaviour key, ST text.
#include "optimize/job_list.hpp"

#include <algorithm>

namespace virtcom::optimize {

namespace {

bool shareResource(const ProcessModel& m, uint32_t a, uint32_t b) {
  for (const Resource& r : m.resources)
    if (std::ranges::find(r.users, a) != r.users.end() && std::ranges::find(r.users, b) != r.users.end()) return true;
  return false;
}

}  // namespace

JobList buildJobList(const ProcessModel& m, const Candidate& c) {
  JobList list;
  for (uint32_t op : c.order) {
    if (c.choice[op] == kSkipped) continue;
    const Alternative& a = m.operations[op].alternatives[static_cast<size_t>(c.choice[op])];
    list.jobs.push_back({op, a.device, a.code, {}});
  }
  const size_t n = list.jobs.size();
  // before[i][j] (i < j): job i must finish before job j starts.
  std::vector<std::vector<char>> before(n, std::vector<char>(n, 0));
  for (size_t j = 0; j < n; ++j)
    for (size_t i = 0; i < j; ++i) {
      const Job& a = list.jobs[i];
      const Job& b = list.jobs[j];
      if (c.waits == WaitRule::Serial) before[i][j] = i + 1 == j;
      else
        before[i][j] = a.device == b.device || m.precedes[a.operation][b.operation] ||
                       (!c.ignoreResources && shareResource(m, a.operation, b.operation));
    }
  // Closed in list order (every edge points forward), then reduced: an edge implied by a path
  // through another job adds no wait.
  for (size_t j = 0; j < n; ++j)
    for (size_t k = 0; k < j; ++k)
      if (before[k][j])
        for (size_t i = 0; i < k; ++i)
          if (before[i][k]) before[i][j] = 1;
  for (size_t j = 0; j < n; ++j) {
    size_t previousOfDevice = n;
    for (size_t i = 0; i < j; ++i)
      if (list.jobs[i].device == list.jobs[j].device) previousOfDevice = i;
    for (size_t i = 0; i < j; ++i) {
      if (!before[i][j] || i == previousOfDevice) continue;
      bool implied = false;
      for (size_t k = i + 1; k < j && !implied; ++k) implied = before[i][k] && before[k][j];
      if (!implied) list.jobs[j].waits.push_back(static_cast<uint32_t>(i + 1));
    }
  }
  // Key: per device its operations in order, each with the operations it waits for.
  std::vector<int64_t> devices;
  for (const Job& j : list.jobs)
    if (std::ranges::find(devices, j.device) == devices.end()) devices.push_back(j.device);
  std::ranges::sort(devices);
  for (int64_t d : devices) {
    list.key += "D" + std::to_string(d) + ":";
    for (const Job& j : list.jobs) {
      if (j.device != d) continue;
      list.key += std::to_string(j.operation) + "/" + std::to_string(j.code);
      std::vector<uint32_t> waitOps;
      for (uint32_t w : j.waits) waitOps.push_back(list.jobs[w - 1].operation);
      std::ranges::sort(waitOps);
      for (uint32_t w : waitOps) list.key += "<" + std::to_string(w);
      list.key += ",";
    }
    list.key += ";";
  }
  return list;
}

std::string jobListSt(const ProcessModel& m, const JobList& list, const std::string& name, const std::string& arrayType) {
  const JobListBinding& b = m.jobList;
  std::string s = name + " : " + arrayType + " := [\n";
  for (size_t i = 0; i < list.jobs.size(); ++i) {
    const Job& j = list.jobs[i];
    std::string item = "(" + b.deviceField + " := " + std::to_string(j.device) + ", " + b.codeField + " := " + std::to_string(j.code);
    for (size_t w = 0; w < j.waits.size() && w < b.waitFields.size(); ++w) item += ", " + b.waitFields[w] + " := " + std::to_string(j.waits[w]);
    item += ")";
    if (i + 1 < list.jobs.size()) item += ",";
    const Operation& op = m.operations[j.operation];
    const Alternative& alt = *std::ranges::find_if(op.alternatives, [&](const Alternative& a) { return a.device == j.device && a.code == j.code; });
    s += "  " + item + std::string(item.size() < 56 ? 56 - item.size() : 1, ' ') + "(* " + std::to_string(i + 1) + " " + op.name +
         " on " + alt.deviceName + " *)\n";
  }
  s += "];\n";
  return s;
}

}  // namespace virtcom::optimize
