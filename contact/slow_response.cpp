#include "contact/slow_response.h"

#include <cmath>
#include <stdexcept>

namespace metrosync {

SlowResponse SlowResponse::refused(std::string why) {
  SlowResponse r;
  r.why_ = why.empty() ? "no averaged response" : std::move(why);
  return r;
}

SlowResponse SlowResponse::constant(AveragedResponse beta) {
  SlowResponse r;
  r.constant_ = beta;
  return r;
}

SlowResponse SlowResponse::dryFriction(double mu) {
  SlowResponse r;
  r.dry_ = true;
  r.mu_ = mu;
  r.constant_ = {0.5, 0.0};  // mu = 0: no friction at all, the free platform's response
  return r;
}

SlowResponse SlowResponse::refusedDry(double mu, std::string why) {
  SlowResponse r = refused(std::move(why));
  r.dry_ = true;
  r.mu_ = mu;
  return r;
}

AveragedResponse SlowResponse::at(double A) const {
  if (!available()) throw std::invalid_argument(why_);
  if (!dry_) return constant_;
  if (mu_ < 0.0) throw std::invalid_argument("averaged response: mu < 0");
  if (mu_ == 0.0) return constant_;
  return coulombResponse(std::fabs(A) / mu_);
}

}  // namespace metrosync
