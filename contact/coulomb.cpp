#include "contact/coulomb.h"
