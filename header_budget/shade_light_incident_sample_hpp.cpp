#include <shade/light/incident_sample.hpp>
