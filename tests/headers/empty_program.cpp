// An empty program that includes the umbrella header: its symbols must hold no static
// initialiser (tests/headers/no_static_init.cmake).
#include <shade/shade.hpp>

int main() { return 0; }
