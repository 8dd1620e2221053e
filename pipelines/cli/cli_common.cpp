#include "cli_common.h"

#include <smooth/errors.h>

#include <iostream>

namespace contourmesh::cli {

int run_guarded(const std::string& command, const std::function<int()>& body) {
  try {
    return body();
  } catch (const InvalidInputError& e) {
    std::cerr << "contourmesh " << command << ": error: " << e.what() << "\n";
    return kBadInput;
  } catch (const CancelledError& e) {
    std::cerr << "contourmesh " << command << ": " << e.what() << "\n";
    return kBadInput;
  } catch (const std::exception& e) {
    std::cerr << "contourmesh " << command << ": internal error: " << e.what() << "\n";
    return kInternal;
  }
}

namespace {
int g_exit_code = kOk;
}  // namespace

void set_exit_code(int code) { g_exit_code = code; }
int last_exit_code() { return g_exit_code; }

void print_json(const nlohmann::json& json) { std::cout << json.dump() << std::endl; }

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace contourmesh::cli
