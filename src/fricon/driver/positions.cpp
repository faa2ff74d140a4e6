#include "fricon/driver/positions.hpp"

#include <stdexcept>

namespace fricon::driver {

Positions::Positions(std::initializer_list<std::pair<const std::string, std::string>> entries) {
  for (const auto& [key, origin] : entries)
    set(key, origin);
}

Positions::Data& Positions::own() {
  if (!data_) {
    data_ = std::make_shared<Data>();
  } else if (data_.use_count() > 1) {
    data_ = std::make_shared<Data>(*data_);  // the origins' strings are shared, not copied
  }
  return *data_;
}

std::size_t Positions::index_of(Data& d, const std::shared_ptr<const std::string>& origin) {
  if (const auto it = d.by_address.find(origin.get()); it != d.by_address.end()) return it->second;
  std::size_t i = 0;
  if (const auto it = d.by_text.find(*origin); it != d.by_text.end()) {
    i = it->second;
  } else {
    i = d.origins.size();
    d.origins.push_back(origin);
    d.by_text.emplace(*origin, i);
  }
  d.by_address.emplace(origin.get(), i);
  return i;
}

void Positions::set(const std::string& key, const std::string& origin) {
  Data& d = own();
  const auto it = d.by_text.find(origin);
  const std::size_t i =
      it != d.by_text.end() ? it->second : index_of(d, std::make_shared<const std::string>(origin));
  d.origin_of.insert_or_assign(key, i);
}

void Positions::set(const std::string& key, const std::shared_ptr<const std::string>& origin) {
  Data& d = own();
  d.origin_of.insert_or_assign(key, index_of(d, origin));
}

const std::string* Positions::find(std::string_view key) const {
  if (!data_) return nullptr;
  const auto it = data_->origin_of.find(key);
  return it == data_->origin_of.end() ? nullptr : data_->origins[it->second].get();
}

const std::string& Positions::at(std::string_view key) const {
  const std::string* origin = find(key);
  if (origin == nullptr) throw std::out_of_range("Positions::at: no position recorded for a key");
  return *origin;
}

std::size_t Positions::text_size() const {
  if (!data_) return 0;
  std::size_t n = 0;
  for (const auto& [key, index] : data_->origin_of)
    n += key.size();
  for (const auto& origin : data_->origins)
    n += origin->size();
  return n;
}

std::map<std::string, std::string, std::less<>> Positions::to_map() const {
  std::map<std::string, std::string, std::less<>> out;
  if (!data_) return out;
  for (const auto& [key, index] : data_->origin_of)
    out.emplace(key, *data_->origins[index]);
  return out;
}

}  // namespace fricon::driver
