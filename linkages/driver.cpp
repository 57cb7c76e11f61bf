// The driver: a crank turning about a fixed pivot, or a slider on a fixed guide.
#include "linkages/linkage_writer.hpp"

namespace kinema::linkage_detail {

void LinkageWriter::choose_driver() {
  if (!linkage_.driver_link.empty()) {
    const auto it = body_index_.find(linkage_.driver_link);
    if (it == body_index_.end() || it->second == 0) {
      fail(linkage_.driver_where, "[driver] link = \"" + linkage_.driver_link + "\" is not a link of [links]");
    }
    driver_body_ = it->second;
    const Body& body = bodies_[driver_body_];
    bool grounded = false;
    for (const Edge& e : edges_)
      grounded = grounded || (!e.slider && ((e.a == 0 && e.b == driver_body_) || (e.b == 0 && e.a == driver_body_)));
    if (!grounded) {
      fail(linkage_.driver_where, "the driver, link \"" + body.name +
                                      "\", is not attached to ground: a crank turns about a fixed pivot (a joint "
                                      "with ground = true on it)");
    }
    if (body.slider >= 0) {
      fail(linkage_.driver_where, "the driver, link \"" + body.name + "\", is a slider block: its angle is its "
                                      "guide's; drive the slider instead ([driver] slider = \"" +
                                      linkage_.joints[std::size_t(body.slider)].name + "\")");
    }
    if (m_.input.dimension != Dimension::angle && !m_.input.values.empty()) {
      fail(linkage_.driver_where, "the driver is a crank (link \"" + body.name + "\"): its values are angles, e.g. "
                                                                             "\"30 deg\"");
    }
    m_.input.dimension = Dimension::angle;
  } else {
    const auto it = joint_index_.find(linkage_.driver_slider);
    if (it == joint_index_.end() || linkage_.joints[it->second].kind != Joint::Kind::slider) {
      fail(linkage_.driver_where, "[driver] slider = \"" + linkage_.driver_slider + "\" is not a slider of [joints]");
    }
    driver_slider_ = static_cast<int>(it->second);
    if (linkage_.joints[it->second].guide != "ground") {
      fail(linkage_.driver_where, "the driver, slider \"" + linkage_.driver_slider +
                                      "\", is not attached to ground: a driven slider moves on a fixed guide "
                                      "(slider = \"ground\")");
    }
    if (m_.input.dimension != Dimension::length && !m_.input.values.empty()) {
      fail(linkage_.driver_where, "the driver is a slider: its values are lengths, e.g. \"0.2 m\"");
    }
    m_.input.dimension = Dimension::length;
  }
}

}  // namespace kinema::linkage_detail
