#include "app/batch/job_line.h"

#include <nlohmann/json.hpp>

#include "engine/base/error.h"

namespace mostyle::cli {
namespace {

using Json = nlohmann::json;

std::string a_json_type(const Json& j) {
  if (j.is_null()) return "null";
  const std::string name = j.type_name();
  return (name[0] == 'a' || name[0] == 'o' ? "an " : "a ") + name;
}

}  // namespace

std::vector<std::string> parse_job_line(std::string_view line, const std::string& source,
                                        int line_number) {
  const std::string where = source + ":" + std::to_string(line_number) + ": ";
  const std::string expected =
      where + "expected a JSON array of strings (the arguments of one mostyle-cli command), found ";
  Json j;
  try {
    j = Json::parse(line.begin(), line.end());
  } catch (const Json::parse_error& e) {
    throw InputError(expected + "invalid JSON at column " + std::to_string(e.byte));
  } catch (const Json::out_of_range&) {
    // "1e400": nlohmann reports a number too large for a double this way, without its column.
    throw InputError(expected + "a number too large for JSON");
  }
  if (!j.is_array()) throw InputError(expected + a_json_type(j));
  std::vector<std::string> args;
  args.reserve(j.size());
  for (size_t k = 0; k < j.size(); ++k) {
    if (!j[k].is_string()) throw InputError(expected + a_json_type(j[k]) + " as item " + std::to_string(k + 1));
    args.push_back(j[k].get<std::string>());
  }
  if (args.empty())
    throw InputError(where + "expected a mostyle-cli command such as [\"blend\", ...], found an empty array");
  // The main program takes no option before its subcommand, so the first argument names it.
  if (args[0] == "batch") throw InputError(where + "a job cannot be a batch itself");
  return args;
}

}  // namespace mostyle::cli
