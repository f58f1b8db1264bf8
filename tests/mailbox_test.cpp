// Mailbox stress: many producers into one lock-free mailbox; nothing lost, nothing duplicated,
// and each sender's messages arrive in the order sent.
#include <doctest/doctest.h>

#include <functional>
#include <thread>
#include <vector>

#include <oneapi/tbb/task_arena.h>
#include <oneapi/tbb/task_group.h>

#include "core/comm/mailbox.h"

using namespace kdswap;

namespace {

constexpr int kProducers = 8;
constexpr int kPerProducer = 100000;

// Producers are plain threads; the consumer drains in arrival order and checks each sender's
// sequence. `consume` runs the consumer loop in whatever context the caller sets up.
void stress(Mailbox& box, const std::function<void(const std::function<void()>&)>& consume) {
  std::vector<std::int64_t> nextExpected(kProducers, 0);
  long received = 0;
  bool inOrder = true;
  double waited = 0;
  std::vector<std::thread> producers;
  consume([&] {
    for (int p = 0; p < kProducers; ++p)
      producers.emplace_back([&box, p] {
        for (int i = 0; i < kPerProducer; ++i) {
          Message m;
          m.source = p;
          m.tag = 1;
          m.header = {i};
          box.post(std::move(m));
        }
      });
    for (long i = 0; i < long(kProducers) * kPerProducer; ++i) {
      Message m = box.take(Mailbox::kAnySource, 1, waited);
      const int p = m.source;
      if (m.header.at(0) != nextExpected[std::size_t(p)]) inOrder = false;
      nextExpected[std::size_t(p)] = m.header[0] + 1;
      ++received;
    }
  });
  for (std::thread& t : producers) t.join();
  CHECK(received == long(kProducers) * kPerProducer);
  CHECK(inOrder);
  for (int p = 0; p < kProducers; ++p) CHECK(nextExpected[std::size_t(p)] == kPerProducer);
  Message extra;
  CHECK_FALSE(box.tryTake(Mailbox::kAnySource, 1, extra));
}

}  // namespace

TEST_CASE("8 producers x 100000 messages into one mailbox: none lost, none duplicated, order kept") {
  Mailbox box;
  tbb::task_arena arena(2);
  stress(box, [&](const std::function<void()>& body) {
    // The consumer is a oneTBB task, so an empty mailbox suspends it instead of spinning.
    arena.execute([&] {
      tbb::task_group consumer;
      consumer.run(body);
      consumer.wait();
    });
  });
}

TEST_CASE("a thread-blocking mailbox passes the same stress: 8 x 100000, none lost, order kept") {
  Mailbox box(Mailbox::WaitMode::BlockThread);
  stress(box, [](const std::function<void()>& body) {
    std::thread consumer(body);
    consumer.join();
  });
}

TEST_CASE("abort wakes a thread-blocked consumer, which then fails instead of hanging") {
  Mailbox box(Mailbox::WaitMode::BlockThread);
  bool failed = false;
  std::thread consumer([&] {
    double waited = 0;
    try {
      box.take(0, 5, waited);
    } catch (const MailboxAborted&) {
      failed = true;
    }
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  box.abort();
  consumer.join();
  CHECK(failed);
}

TEST_CASE("take picks the message matching source and tag and leaves the others queued") {
  Mailbox box;
  for (int source : {3, 1, 2}) {
    Message m;
    m.source = source;
    m.tag = source * 10;
    box.post(std::move(m));
  }
  Message m;
  CHECK(box.tryTake(2, 20, m));
  CHECK(m.source == 2);
  CHECK_FALSE(box.tryTake(2, 20, m));
  CHECK_FALSE(box.tryTake(3, 99, m));
  CHECK(box.tryTake(Mailbox::kAnySource, 10, m));
  CHECK(m.source == 1);
}

TEST_CASE("abort wakes a suspended consumer, which then fails instead of hanging") {
  Mailbox box;
  bool failed = false;
  tbb::task_arena arena(2);
  arena.execute([&] {
    tbb::task_group group;
    group.run([&] {
      double waited = 0;
      try {
        box.take(0, 5, waited);
      } catch (const MailboxAborted&) {
        failed = true;
      }
    });
    std::thread aborter([&] {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
      box.abort();
    });
    group.wait();
    aborter.join();
  });
  CHECK(failed);
}
