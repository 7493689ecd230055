// A helper header beside the exercise file
#pragma once
constexpr int kPlaneHelper = 42;
