#include "big.h"
// RAYLAB-HONEST-CODE 04_sphere
