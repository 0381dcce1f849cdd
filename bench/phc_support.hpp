// Talking to PHCpack's `phc -b` (Debian package phcpack): writing a real polynomial system in
// its input syntax and reading the solutions back. Shared by the five-point benchmark and
// the cross-check test.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "nbar/synthesis/polynomial.hpp"

namespace nbar::phc {

inline bool available() { return std::system("command -v phc > /dev/null 2>&1") == 0; }

// Real coefficients only (the imaginary parts are dropped: the caller's system is real).
inline std::string input(const synthesis::PolynomialSystem& f, const std::vector<std::string>& names) {
  std::ostringstream out;
  out.precision(17);
  out << f.equations() << "\n";
  for (const auto& p : f.polynomials()) {
    for (const auto& [e, c] : p.terms()) {
      out << (c.real() < 0 ? " - " : " + ") << std::abs(c.real());
      for (size_t v = 0; v < e.size(); ++v)
        for (int k = 0; k < e[v]; ++k) out << "*" << names[v];
    }
    out << ";\n";
  }
  return out.str();
}

struct Result {
  std::vector<std::map<std::string, synthesis::Complex>> regular;  // regular solutions by name
  long reported_regular = -1;  // PHCpack's own count ("Number of regular solutions")
};

// Runs `phc -b` in `dir`; nullopt when phc fails.
inline std::optional<Result> solve(const synthesis::PolynomialSystem& f, const std::vector<std::string>& names,
                                   const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  const auto in = dir / "in.phc", out = dir / "out.phc";
  std::ofstream(in) << input(f, names);
  std::filesystem::remove(out);
  const std::string command =
      std::string("phc -b ").append(in.string()).append(" ").append(out.string()).append(" > /dev/null 2>&1");
  if (std::system(command.c_str()) != 0) return std::nullopt;
  Result result;
  std::ifstream file(out);
  std::string line;
  std::map<std::string, synthesis::Complex> current;
  bool reading = false;
  while (std::getline(file, line)) {
    if (line.find("the solution for t :") != std::string::npos) {
      reading = true;
      current.clear();
    } else if (reading && line.rfind("==", 0) == 0) {
      reading = false;
      if (line.find("regular") != std::string::npos && line.find("singular") == std::string::npos)
        result.regular.push_back(current);
    } else if (reading) {
      std::istringstream fields(line);
      std::string name, colon;
      double re = 0, im = 0;
      if (fields >> name >> colon >> re >> im) current[name] = {re, im};
    } else if (line.find("Number of regular solutions") != std::string::npos) {
      result.reported_regular = std::strtol(line.substr(line.find(':') + 1).c_str(), nullptr, 10);
    }
  }
  return result;
}

}  // namespace nbar::phc
