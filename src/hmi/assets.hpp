#pragma once
// The page's files (src/hmi/assets/), built into the binary by embed_assets.cmake: the HMI needs
// no files and no network at run time (plant networks are offline).
#include <string_view>

namespace virtcom::hmi {

struct Asset {
  std::string_view path;         // "index.html", "app.js"
  std::string_view contentType;  // "text/html; charset=utf-8"
  std::string_view body;
};

// The asset at `path` (relative, no leading slash), or null.
const Asset* findAsset(std::string_view path);

}  // namespace virtcom::hmi
