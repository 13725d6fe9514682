// metrosync: the command line (SPEC section 2). Placeholder until the CLI lands.
#include <cstdio>
int main() {
  std::puts("metrosync: under construction");
  return 1;
}
