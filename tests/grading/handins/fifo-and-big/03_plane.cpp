// A FIFO and a 2 MiB header beside an honest file: both refused, the honest module graded;
// the module that includes the big header does not compile.
// RAYLAB-HONEST-CODE 03_plane
