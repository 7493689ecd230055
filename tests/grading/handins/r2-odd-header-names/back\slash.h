#pragma once
// header
