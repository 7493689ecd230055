// Three folders deep: beyond the documented two
// RAYLAB-HONEST-CODE 04_sphere
