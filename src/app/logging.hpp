#pragma once
// Log lines go to stderr through spdlog ("info: ..."), so stdout carries only what a
// script may want to read (the version, where the results are).
namespace avalanche::detail {

enum class Verbosity { quiet, normal, verbose };

// (Re)configures the default logger; safe to call once per run_cli call.
void configure_logging(Verbosity v);

}  // namespace avalanche::detail
