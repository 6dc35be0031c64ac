#pragma once
// What a served cell's Modbus tables name for the write audit (core/write_audit.hpp): the
// signals of its map, "Press.start (coil 3): FALSE -> TRUE", their values as the signal (the
// register value times the scale) and their place as the cell file writes it ("holding 4").
// The addresses are those of a TableImage (tableBaseAddress).
#include <memory>

#include "core/write_audit.hpp"
#include "proto/modbus/signal_map.hpp"

namespace virtcom::proto::modbus {

std::unique_ptr<AuditedNames> auditedSignals(const SignalMap& map);

}  // namespace virtcom::proto::modbus
