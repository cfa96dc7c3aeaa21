#pragma once
// A header made to exceed the 60000-line budget of core/ (tests/headers/budget.cmake must
// reject it): the stream and regular-expression headers a core header must not include.

#include <iostream>
#include <regex>
#include <sstream>
