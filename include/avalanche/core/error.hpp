#pragma once
// One error type for the whole project (STYLE.md convention 7). Every error says
// what it concerns (file, key, cell) and maps to a documented exit code.
#include <stdexcept>
#include <string>

namespace avalanche {

enum class ExitCode : int {
    ok = 0,
    usage = 2,           // bad command line or scenario value
    input = 3,           // unreadable or invalid input file
    output = 4,          // output folder exists, is unwritable, or the disk is full
    numerical = 5,       // NaN/Inf or negative depth detected in the state
    interrupted = 6,     // stopped by a signal
    internal = 70,       // a bug: an invariant failed
};

class Error : public std::runtime_error {
public:
    Error(ExitCode code, const std::string& message) : std::runtime_error(message), code_(code) {}
    [[nodiscard]] ExitCode code() const { return code_; }

private:
    ExitCode code_;
};

// Bad user value: names the key (scenario key or flag) and what is expected.
class ConfigError : public Error {
public:
    ConfigError(const std::string& key, const std::string& what)
        : Error(ExitCode::usage, key + ": " + what) {}
};

// Unreadable or invalid input file.
class InputError : public Error {
public:
    InputError(const std::string& file, const std::string& what)
        : Error(ExitCode::input, file + ": " + what) {}
};

class OutputError : public Error {
public:
    OutputError(const std::string& path, const std::string& what)
        : Error(ExitCode::output, path + ": " + what) {}
};

// A non-finite or negative value in the solver state, with where and when.
class NumericalError : public Error {
public:
    NumericalError(const std::string& what, int i, int j, double x, double y, double t)
        : Error(ExitCode::numerical, what + " at cell (i=" + std::to_string(i) + ", j=" +
                                         std::to_string(j) + "), x=" + std::to_string(x) +
                                         " m, y=" + std::to_string(y) +
                                         " m, t=" + std::to_string(t) + " s"),
          i_(i), j_(j), t_(t) {}
    [[nodiscard]] int i() const { return i_; }
    [[nodiscard]] int j() const { return j_; }
    [[nodiscard]] double t() const { return t_; }

private:
    int i_, j_;
    double t_;
};

}  // namespace avalanche
