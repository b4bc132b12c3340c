#include "solve/core/junction_state.hpp"

namespace asperity {

JunctionState::JunctionState(const std::vector<double>& areas, const ContactLaw& law)
    : A0(areas),
      anchor(areas.size(), 0.0),
      force(areas.size(), 0.0),
      area(areas),
      k(areas.size()),
      f_s(areas.size()),
      pinned(areas.size(), 1),
      intact(areas.size(), 1) {
  for (std::size_t i = 0; i < areas.size(); ++i) set_contact(i, contact_at_area(law, A0[i], A0[i]));
}

}  // namespace asperity
