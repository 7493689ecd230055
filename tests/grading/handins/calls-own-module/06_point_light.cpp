// RAYLAB-HONEST-CODE 06_point_light
