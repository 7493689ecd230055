float helper_t() { return 1.0f; }
