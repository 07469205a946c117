#include "experiments/cli/cli.hpp"

int main(int argc, char** argv) { return tcb::run_cli(argc, argv); }
