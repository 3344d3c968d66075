#include "reconcile/report.hpp"
