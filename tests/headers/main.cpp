// The header-alone objects are linked in beside this main; compiling them is the test.
int main() { return 0; }
