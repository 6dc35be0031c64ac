#include "cli/external_wires.hpp"

#include "core/cell_diagnostic_codes.hpp"

namespace virtcom::cli {

void reportUnmatchedPrefixes(const std::vector<cell::ExternalWire>& wires, const std::vector<bool>& found, Diagnostics& diags,
                             const std::function<std::string(const cell::ExternalWire&, const std::string&, const std::string&)>& message) {
  for (size_t i = 0; i < wires.size() && i < found.size(); ++i) {
    const cell::ExternalWire& w = wires[i];
    if (w.prefixGroup < 0 || (i > 0 && wires[i - 1].prefixGroup == w.prefixGroup)) continue;  // a group's first port
    bool any = false;
    for (size_t j = i; j < wires.size() && wires[j].prefixGroup == w.prefixGroup; ++j) any |= found[j];
    if (any) continue;
    std::string device = w.port.substr(0, w.port.find('.'));
    std::string prefix = w.variable.substr(0, w.variable.size() - (w.port.size() - device.size()));
    diags.error(celldiag::C030, w.loc, message(w, device, prefix));
  }
}

}  // namespace virtcom::cli
