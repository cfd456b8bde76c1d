// The contact a law is being called for, while the contact layer calls it (a
// thread's own): what an error raised inside the law can name (a law written in
// Python, docs/guide/python.md "When a Python law returns a bad value"). The
// contact layer sets it around each call of linearize and advance with
// CallSiteScope; outside a contact (a curve, a fit) it is unset (contact < 0).
#pragma once

namespace rheodda::laws {

struct CallSite {
  long contact = -1;     ///< the contact's id (contacts.csv `id`); < 0: no contact
  int vertex_block = -1;  ///< the block of its vertex
  int vertex = -1;        ///< the vertex
  int edge_block = -1;    ///< the block of its edge
  int edge = -1;          ///< the edge
  int joint_set = -1;     ///< its joint set (index)
};

/// The call site now (the calling thread's).
inline CallSite& current_call_site() {
  thread_local CallSite site;
  return site;
}

/// Sets the call site for its lifetime, restoring the one before.
class CallSiteScope {
 public:
  explicit CallSiteScope(const CallSite& site) : saved_(current_call_site()) { current_call_site() = site; }
  ~CallSiteScope() { current_call_site() = saved_; }
  CallSiteScope(const CallSiteScope&) = delete;
  CallSiteScope& operator=(const CallSiteScope&) = delete;

 private:
  CallSite saved_;
};

}  // namespace rheodda::laws
