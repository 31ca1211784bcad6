// Compiled only so that its target builds the shared precompiled header (scantling_add_pch_hosts
// in ScantlingHelpers.cmake); the test host links it as a program, hence main.
int main() { return 0; }
