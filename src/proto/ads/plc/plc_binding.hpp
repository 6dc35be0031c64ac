#pragma once
// Serving a soft PLC over ADS: the two calls a scan loop makes around each scan.
#include "plc/runtime.hpp"
#include "proto/ads/server.hpp"

namespace virtcom::proto::ads {

// Before a scan: applies a client's RUN/STOP and every queued write (located inputs also go to
// the external input image, so the scan's input copy keeps them). No allocation.
void beforeScan(Server& server, plc::Runtime& runtime);
// After a scan: publishes the memory image and the PLC state to the server. No allocation.
void afterScan(Server& server, plc::Runtime& runtime);

uint16_t adsStateOf(plc::PlcState s);

}  // namespace virtcom::proto::ads
