// RAYLAB-HONEST-CODE 01_pixel_loop
