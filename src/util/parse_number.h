// Parsing numbers from text the whole way (no trailing characters, finite values only), for
// configs, command-line values and compact specs such as "x,y,z,qw,qx,qy,qz".
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace contactlab {

// The number TEXT spells (surrounding blanks allowed), or nullopt.
std::optional<double> ParseDouble(std::string_view text);
std::optional<long long> ParseInteger(std::string_view text);

// Comma-separated finite numbers; throws Error("WHERE: 'item' is not a number").
std::vector<double> ParseNumberList(std::string_view text, std::string_view where);

}  // namespace contactlab
