// MPI bridge of the hybrid network: one progress thread per rank makes every MPI call.
//
// Wire format of one Message: an envelope of six int64 (source node, destination node, tag, and
// the lengths of header, payload and text) with kEnvelopeTag, then each non-empty part as its own
// message with kBodyTag, sent straight from the Message's buffers (no packing copy). MPI does not
// let two messages from one rank overtake each other when one receive could match both, and the
// progress thread probes with MPI_ANY_TAG and receives an envelope's parts before probing again,
// so parts follow their envelope and node pairs keep their order. The host is node -1 in the
// envelope, so it needs no tag range of its own. Abort reasons travel as text with kAbortTag.
#include "core/comm/mpi_network.h"

#if KDSWAP_HAVE_MPI

#include <chrono>
#include <climits>
#include <condition_variable>
#include <deque>
#include <list>
#include <thread>

// The C API only: Open MPI's deprecated C++ bindings would need libmpi_cxx.
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>

#include "core/comm/communicator.h"
#include "core/util/check.h"
#include "core/util/clock.h"
#include "core/util/error.h"

namespace kdswap {
namespace {

constexpr int kEnvelopeTag = 1;
constexpr int kBodyTag = 2;
constexpr int kAbortTag = 3;

int checkedCount(std::size_t n, const char* what) {
  if (n > std::size_t(INT_MAX))
    throw Error(std::string("MPI send: ") + what + " of " + std::to_string(n) + " elements exceeds one MPI message");
  return int(n);
}

}  // namespace

// ---------------------------------------------------------------------------------------------
MpiSession::MpiSession(int& argc, char**& argv) {
  int provided = 0;
  if (MPI_Init_thread(&argc, &argv, MPI_THREAD_SERIALIZED, &provided) != MPI_SUCCESS)
    throw Error("MPI start-up: MPI_Init_thread failed");
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  if (provided < MPI_THREAD_SERIALIZED) {
    MPI_Finalize();
    throw Error("MPI start-up: the library gives thread level " + std::to_string(provided) +
                "; kdswap-mpi needs MPI_THREAD_SERIALIZED (its progress thread makes the MPI calls)");
  }
}

MpiSession::~MpiSession() { MPI_Finalize(); }

// ---------------------------------------------------------------------------------------------
//! Everything the progress thread owns. Other threads touch only the queue (under mutex_).
class MpiNetwork::Progress {
 public:
  Progress(MpiNetwork& net, double stallSeconds) : net_(net), stallSeconds_(stallSeconds), thread_([this] { run(); }) {}
  ~Progress() { stop(); }

  //! Any thread: queue `m` for node `dest` on another rank (dest < 0: broadcast abort text).
  void enqueue(int dest, Message m) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      queue_.push_back(Outgoing{dest, std::move(m)});
    }
    wake_.notify_one();
  }

  //! Main thread: runs the termination protocol (see finish()) and joins the thread.
  void stop() {
    if (!thread_.joinable()) return;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      finishing_ = true;
    }
    wake_.notify_one();
    thread_.join();
  }

 private:
  struct Outgoing {
    int dest;  //!< destination node (or kHost); kBroadcastAbort for an abort reason
    Message message;
  };
  //! A message handed to MPI_Isend; the buffers stay alive here until every request completes.
  struct InFlight {
    std::int64_t envelope[6];
    Message message;
    std::vector<MPI_Request> requests;
  };
  static constexpr int kBroadcastAbort = INT_MIN;

  void run() {
    int idle = 0;
    double lastTraffic = nowSeconds();
    std::uint64_t lastCount = net_.traffic_.load(std::memory_order_relaxed);
    MPI_Request barrier = MPI_REQUEST_NULL;
    bool inBarrier = false;
    for (;;) {
      bool busy = startQueuedSends();
      busy |= completeSends();
      busy |= receiveArrived();
      bool finishing;
      {
        std::lock_guard<std::mutex> lock(mutex_);
        finishing = finishing_ && queue_.empty();
      }
      if (finishing && inFlight_.empty()) {
        // Every local task has ended and our sends are complete. The barrier completes once all
        // ranks are here; receiving goes on meanwhile so larger sends to us can complete too.
        if (!inBarrier) {
          MPI_Ibarrier(MPI_COMM_WORLD, &barrier);
          inBarrier = true;
        }
        int done = 0;
        MPI_Test(&barrier, &done, MPI_STATUS_IGNORE);
        if (done) {
          // After a successful frame every message sent was consumed. After an abort some eager
          // messages may still be unmatched; take what has arrived so none is left at finalize.
          while (receiveArrived()) {
          }
          return;
        }
      }
      const std::uint64_t count = net_.traffic_.load(std::memory_order_relaxed);
      if (busy || count != lastCount) {
        lastCount = count, lastTraffic = nowSeconds(), idle = 0;
        continue;
      }
      if (!inBarrier && !net_.aborted() && nowSeconds() - lastTraffic > stallSeconds_) {
        const std::string waits = net_.describeWaits();
        if (waits != "no node is waiting")
          net_.abortAll("rank " + std::to_string(net_.rank_) + ": stalled: no message for " +
                        std::to_string(int(stallSeconds_)) + " s; " + waits);
        lastTraffic = nowSeconds();
      }
      // Idle: yield a little (latency of an exchange), then sleep in short steps; a queued send
      // wakes us at once, arriving MPI messages are seen within one step.
      if (++idle < 64) {
        std::this_thread::yield();
      } else {
        std::unique_lock<std::mutex> lock(mutex_);
        wake_.wait_for(lock, std::chrono::microseconds(200), [this] { return !queue_.empty() || finishing_; });
      }
    }
  }

  bool startQueuedSends() {
    std::deque<Outgoing> batch;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      batch.swap(queue_);
    }
    for (Outgoing& out : batch) {
      if (out.dest == kBroadcastAbort) {
        broadcastAbort(std::move(out.message.text));
        continue;
      }
      inFlight_.emplace_back();
      InFlight& f = inFlight_.back();
      f.message = std::move(out.message);
      const Message& m = f.message;
      const int to = net_.rankOf(out.dest);
      const std::int64_t env[6] = {m.source, out.dest, m.tag, std::int64_t(m.header.size()),
                                   std::int64_t(m.payload.size()), std::int64_t(m.text.size())};
      std::copy(env, env + 6, f.envelope);
      auto post = [&](const void* data, int count, MPI_Datatype type, int tag) {
        f.requests.emplace_back();
        MPI_Isend(data, count, type, to, tag, MPI_COMM_WORLD, &f.requests.back());
      };
      post(f.envelope, 6, MPI_INT64_T, kEnvelopeTag);
      if (!m.header.empty()) post(m.header.data(), checkedCount(m.header.size(), "header"), MPI_INT64_T, kBodyTag);
      if (!m.payload.empty()) post(m.payload.data(), checkedCount(m.payload.size(), "payload"), MPI_FLOAT, kBodyTag);
      if (!m.text.empty()) post(m.text.data(), checkedCount(m.text.size(), "text"), MPI_CHAR, kBodyTag);
    }
    return !batch.empty();
  }

  void broadcastAbort(std::string reason) {
    inFlight_.emplace_back();
    InFlight& f = inFlight_.back();
    f.message.text = std::move(reason);
    for (int r = 0; r < net_.ranks_; ++r) {
      if (r == net_.rank_) continue;
      f.requests.emplace_back();
      MPI_Isend(f.message.text.data(), int(f.message.text.size()), MPI_CHAR, r, kAbortTag, MPI_COMM_WORLD,
                &f.requests.back());
    }
  }

  bool completeSends() {
    bool any = false;
    for (auto it = inFlight_.begin(); it != inFlight_.end();) {
      int done = 0;
      MPI_Testall(int(it->requests.size()), it->requests.data(), &done, MPI_STATUSES_IGNORE);
      if (done) {
        it = inFlight_.erase(it);
        any = true;
      } else {
        ++it;
      }
    }
    return any;
  }

  //! Receives every message that has arrived; true if there was one.
  bool receiveArrived() {
    bool any = false;
    for (;;) {
      int flag = 0;
      MPI_Status status;
      MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &status);
      if (!flag) return any;
      any = true;
      if (status.MPI_TAG == kAbortTag) {
        int n = 0;
        MPI_Get_count(&status, MPI_CHAR, &n);
        std::string reason(std::size_t(n), '\0');
        MPI_Recv(reason.data(), n, MPI_CHAR, status.MPI_SOURCE, kAbortTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        net_.abortLocal(reason);
      } else if (status.MPI_TAG == kEnvelopeTag) {
        receiveMessage(status.MPI_SOURCE);
      } else {
        net_.abortAll("rank " + std::to_string(net_.rank_) + ": MPI message with unexpected tag " +
                      std::to_string(status.MPI_TAG) + " from rank " + std::to_string(status.MPI_SOURCE));
        MPI_Recv(nullptr, 0, MPI_BYTE, status.MPI_SOURCE, status.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      }
    }
  }

  void receiveMessage(int fromRank) {
    std::int64_t env[6];
    MPI_Recv(env, 6, MPI_INT64_T, fromRank, kEnvelopeTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    Message m;
    m.source = int(env[0]);
    m.tag = int(env[2]);
    m.header.resize(std::size_t(env[3]));
    m.payload.resize(std::size_t(env[4]));
    m.text.resize(std::size_t(env[5]));
    // The parts were sent right after the envelope, so these receives only wait for the wire.
    if (!m.header.empty())
      MPI_Recv(m.header.data(), int(env[3]), MPI_INT64_T, fromRank, kBodyTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    if (!m.payload.empty())
      MPI_Recv(m.payload.data(), int(env[4]), MPI_FLOAT, fromRank, kBodyTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    if (!m.text.empty())
      MPI_Recv(m.text.data(), int(env[5]), MPI_CHAR, fromRank, kBodyTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    const int dest = int(env[1]);
    if (!net_.isLocal(dest)) {
      net_.abortAll("rank " + std::to_string(net_.rank_) + ": received a message for node " + std::to_string(dest) +
                    ", which lives on rank " + std::to_string(net_.rankOf(dest)));
      return;
    }
    net_.mailbox(dest).post(std::move(m));
    net_.noteTraffic();
  }

  friend class MpiNetwork;
  MpiNetwork& net_;
  double stallSeconds_;
  std::mutex mutex_;                  //!< guards queue_ and finishing_
  std::condition_variable wake_;      //!< a send was queued, or finish() was called
  std::deque<Outgoing> queue_;        //!< sends waiting for the progress thread, in call order
  bool finishing_ = false;
  std::list<InFlight> inFlight_;      //!< progress thread only
  std::thread thread_;                //!< last member: starts after the rest is built
};

// ---------------------------------------------------------------------------------------------
MpiNetwork::MpiNetwork(int nodesPerRank, double stallSeconds) : perRank_(nodesPerRank) {
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks_);
  const int boxes = perRank_ + (rank_ == 0 ? 1 : 0);
  for (int i = 0; i < boxes; ++i) mailboxes_.push_back(std::make_unique<Mailbox>());
  progress_ = std::make_unique<Progress>(*this, stallSeconds);
}

MpiNetwork::~MpiNetwork() { finish(); }

Mailbox& MpiNetwork::mailbox(int node) {
  if (node == Communicator::kHost) {
    KDSWAP_CHECK_EQ(rank_, 0);
    return *mailboxes_[std::size_t(perRank_)];
  }
  KDSWAP_CHECK(isLocal(node));
  return *mailboxes_[std::size_t(node - firstLocalNode())];
}

void MpiNetwork::deliver(int dest, Message message) {
  noteTraffic();
  if (isLocal(dest))
    mailbox(dest).post(std::move(message));
  else
    progress_->enqueue(dest, std::move(message));
}

void MpiNetwork::abortLocal(const std::string& reason) {
  {
    std::lock_guard<std::mutex> lock(reasonMutex_);
    if (reason_.empty()) reason_ = reason;
  }
  aborted_.store(true, std::memory_order_release);
  for (auto& box : mailboxes_) box->abort();
}

void MpiNetwork::abortAll(const std::string& reason) {
  const bool first = !aborted();
  abortLocal(reason);
  // Tell the other ranks once; a rank that learnt of the abort from another need not repeat it.
  if (first) {
    Message m;
    m.text = reason;
    progress_->enqueue(Progress::kBroadcastAbort, std::move(m));
  }
}

std::string MpiNetwork::abortReason() const {
  std::lock_guard<std::mutex> lock(reasonMutex_);
  return reason_;
}

std::string MpiNetwork::describeWaits() const {
  std::string text;
  for (std::size_t i = 0; i < mailboxes_.size(); ++i) {
    int source = 0, tag = 0;
    if (!mailboxes_[i]->waitingFor(source, tag)) continue;
    const bool host = int(i) == perRank_;
    if (!text.empty()) text += "; ";
    text += (host ? std::string("host") : "node " + std::to_string(firstLocalNode() + int(i))) + " waits for " +
            (source < 0 ? std::string("the host") : "node " + std::to_string(source)) + " on rank " +
            std::to_string(rankOf(source)) + " (tag " + std::to_string(tag) + ")";
  }
  return text.empty() ? "no node is waiting" : text;
}

void MpiNetwork::finish() {
  if (progress_) progress_->stop();
}

}  // namespace kdswap

#endif  // KDSWAP_HAVE_MPI
