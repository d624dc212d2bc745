#pragma once
#include <vector>

namespace tray {

/// One pixel's summed filter weights per object id and per material id: the input of
/// Cryptomatte's ranking filter (Cryptomatte specification, "Ranking Pixel Filter": every sample
/// adds its filter weight to its id; the sums divided by the total weight are the coverages).
/// Id -1 is a sample that hit nothing. The renderer passes one only when Cryptomatte layers are
/// requested, so other renders pay nothing for it.
struct IdCoverage {
  struct Entry {
    int id;
    double weight;
  };
  std::vector<Entry> objects, materials;  ///< few entries per pixel: linear search is fastest
  double total = 0;

  void clear() {
    objects.clear();
    materials.clear();
    total = 0;
  }
  void add(int objectId, int materialId, double weight) {
    addTo(objects, objectId, weight);
    addTo(materials, materialId, weight);
    total += weight;
  }

 private:
  static void addTo(std::vector<Entry>& entries, int id, double weight) {
    for (Entry& e : entries)
      if (e.id == id) {
        e.weight += weight;
        return;
      }
    entries.push_back({id, weight});
  }
};

}  // namespace tray
