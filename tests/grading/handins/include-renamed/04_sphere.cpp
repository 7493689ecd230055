// The reference's own file, compiled as the student's: its namespace renamed by a macro
// so that no raylab::reference symbol is left for the grader's nm check to find. Only the
// compile sandbox stops it: bubblewrap shows no path to solutions/, and without
// namespaces (RAYLAB_SANDBOX=none, ctest grading/adversarial-no-namespaces/*) the
// compiler runs as nobody and solutions/ is closed to other users.
#define reference student
#include "@ROOT@/solutions/04_sphere.cpp"
