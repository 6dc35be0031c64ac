#pragma once
// The ADS view of a compiled program: every global and program variable as a TwinCAT-style
// symbol in index group 0x4040 (IO = its address in the memory image), every type they use with
// TwinCAT's type ids and layouts, and any deeper path resolved on demand.
#include "bytecode/module.hpp"
#include "proto/ads/symbol_table.hpp"

namespace virtcom::proto::ads {

// `m` must outlive the table (paths are resolved against it). Allocates; called once at start.
SymbolTable buildSymbolTable(const bc::Module& m);

// The ADS data type id (ADST_*) of an elementary type (docs/ads.md, Wire reference).
uint32_t adsTypeOf(ElemType e);

}  // namespace virtcom::proto::ads
