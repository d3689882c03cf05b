// certcyl: certified cylinder intersection queries from the command line.
#include <CLI/CLI.hpp>

#include <iostream>

#include "demo.hpp"

int main(int argc, char** argv) {
  CLI::App app{"certcyl: exact cylinder intersection queries and where floating point gets them wrong"};
  app.require_subcommand(1);

  CLI::App* demo = app.add_subcommand("demo", "Answer a few built-in queries of each kind in every number type");

  CLI11_PARSE(app, argc, argv);

  if (demo->parsed()) return certcyl::cli::run_demo(std::cout);
  return 0;
}
