// reenact-server: see server/app/cli.h for the command line.
#include <iostream>

#include "server/app/cli.h"

int main(int argc, char** argv) {
  return reenact::server::RunServerCli(argc, argv, std::cout, std::cerr);
}
