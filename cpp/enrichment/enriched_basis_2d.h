// Kept for cpp/contact until it includes enrichment/enriched_basis.h (the
// enriched basis in any dimension); nothing else includes this file.
#pragma once

#include "enrichment/enriched_basis.h"
