// The benchmarks' command-line lists ("--models bunny,spot", "--sizes 300000,1000000"): the items between commas.
#pragma once

#include <sstream>
#include <string>
#include <vector>

/// The comma-separated items of s, in order (an empty item between two commas is kept; no trailing empty item).
inline std::vector<std::string> splitCommaList(const std::string& s)
{
  std::vector<std::string> out;
  std::stringstream in(s);
  std::string item;
  while (std::getline(in, item, ','))
  {
    out.push_back(item);
  }
  return out;
}
