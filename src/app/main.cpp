// frugal: the commands users run daily (app/Cli.h frugalProgram).
#include "app/Cli.h"

int main(int argc, char** argv) { return frugal::runMain(frugal::frugalProgram(), argc, argv); }
