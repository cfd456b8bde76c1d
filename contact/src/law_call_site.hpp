// The call site a contact's law is called from (laws/call_site.hpp; internal to
// ContactSystem's files): set around each call of linearize and advance, so that an
// error a law raises (a law written in Python) names the contact.
#pragma once

#include "rheodda/contact/contact_system.hpp"
#include "rheodda/laws/call_site.hpp"

namespace rheodda::contact {

inline laws::CallSite law_call_site(const Contact& c) {
  return {static_cast<long>(c.id), c.key.vblock, c.key.vertex, c.key.eblock, c.key.edge, c.joint_set};
}

}  // namespace rheodda::contact
