// libFuzzer harness: the PLY reader, through read_point_cloud on a `.ply` (the vertex element)
// and through PlyReader over every element (what mesh reading uses).
#include "fuzz/harness.hpp"
#include "vantage/io/cloud_io.hpp"
#include "vantage/io/ply.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = vantage::fuzz::write_input(data, size, "cloud.ply");
  vantage::fuzz::expect_clean([&] { vantage::read_point_cloud(path); });
  vantage::fuzz::expect_clean([&] {
    const vantage::PlyReader ply(std::string_view(reinterpret_cast<const char*>(data), size));
    if (ply.elements().empty()) return;
    double sum = 0.0;  // touch every value read
    ply.read(ply.elements().size() - 1,
             [&](std::size_t e, std::uint64_t, const vantage::PlyRecord& record) {
               const auto& properties = ply.elements()[e].properties;
               for (std::size_t k = 0; k < properties.size(); ++k) {
                 if (properties[k].is_list) {
                   for (const double v : record.list(k)) sum += v;
                 } else {
                   sum += record.scalar(k);
                 }
               }
             });
    vantage::fuzz::sink = sum;
  });
  return 0;
}
