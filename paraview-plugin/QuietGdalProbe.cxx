// ParaView's reader factory asks every reader whether it can read a file; for a .las or .laz file that includes the
// GDAL raster reader, whose probe fails and prints "ERROR 4: `file.las' not recognized as a supported file format"
// on every open of a file the GLS LAS Reader reads. This plugin file (loaded with the plugin, nothing to call) puts a
// filter in front of GDAL's error handler that drops exactly that message for .las and .laz files and hands every
// other message to the handler it replaces.
#include <cpl_error.h>

#include <cctype>
#include <cstring>
#include <string>

namespace
{

CPLErrorHandler previousHandler = nullptr;

/// Whether `message` is GDAL's failed probe of a .las or .laz file ("`<path>.las' not recognized as a supported file
/// format.").
bool isLasProbe(CPLErrorNum number, const char* message)
{
  if (number != CPLE_OpenFailed || !message || !std::strstr(message, "' not recognized as a supported file format"))
  {
    return false;
  }
  std::string m(message);
  const auto quote = m.find("' not recognized");
  std::string name = m.substr(0, quote);
  for (char& c : name)
  {
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  const auto endsWith = [&name](const char* ext) {
    const std::size_t n = std::strlen(ext);
    return name.size() >= n && name.compare(name.size() - n, n, ext) == 0;
  };
  return endsWith(".las") || endsWith(".laz");
}

void CPL_STDCALL quietLasProbe(CPLErr type, CPLErrorNum number, const char* message)
{
  if (isLasProbe(number, message))
  {
    return;
  }
  if (previousHandler)
  {
    previousHandler(type, number, message);
  }
  else
  {
    CPLDefaultErrorHandler(type, number, message);
  }
}

/// Installs the filter when the plugin's library is loaded.
struct InstallQuietLasProbe
{
  InstallQuietLasProbe() { previousHandler = CPLSetErrorHandler(quietLasProbe); }
};
const InstallQuietLasProbe install;

} // namespace
